#include "geometry/sph/gauss_legendre.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using rbcflow::gauss_legendre;

TEST(GaussLegendre, IntegratesPolynomialsUpToDegree2nMinus1Exactly) {
  for (int n : {1, 2, 5, 16, 64, 200}) {
    const auto rule = gauss_legendre(n);
    for (int d = 0; d <= 2 * n - 1; d += (n > 20 ? 7 : 1)) {
      double sum = 0.0;
      for (int i = 0; i < n; ++i) sum += rule.weights[i] * std::pow(std::cos(rule.theta[i]), d);
      const double exact = (d % 2 == 0) ? 2.0 / (d + 1) : 0.0;
      EXPECT_NEAR(sum, exact, 1e-14) << "n = " << n << ", degree " << d;
    }
  }
}

TEST(GaussLegendre, NodesAscendInThetaAndAreSymmetric) {
  const auto rule = gauss_legendre(33);
  for (int i = 0; i + 1 < 33; ++i) EXPECT_LT(rule.theta[i], rule.theta[i + 1]);
  for (int i = 0; i < 33; ++i) {
    EXPECT_NEAR(rule.theta[i] + rule.theta[32 - i], std::numbers::pi, 1e-15);
    EXPECT_DOUBLE_EQ(rule.weights[i], rule.weights[32 - i]);
  }
  EXPECT_NEAR(rule.theta[16], std::numbers::pi / 2, 1e-15);
}

TEST(GaussLegendre, MatchesTabulatedThreePointRule) {
  const auto rule = gauss_legendre(3);  // nodes -sqrt(3/5), 0, sqrt(3/5); weights 5/9, 8/9, 5/9
  EXPECT_NEAR(std::cos(rule.theta[0]), std::sqrt(0.6), 1e-15);
  EXPECT_NEAR(rule.weights[0], 5.0 / 9.0, 1e-15);
  EXPECT_NEAR(rule.weights[1], 8.0 / 9.0, 1e-15);
}

TEST(GaussLegendre, RejectsZeroNodes) { EXPECT_THROW(gauss_legendre(0), std::invalid_argument); }
