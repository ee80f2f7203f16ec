#include "geometry/sph/legendre.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "geometry/sph/gauss_legendre.h"

using rbcflow::legendre_theta_tables;

TEST(Legendre, MatchesClosedFormsOfLowDegree) {
  Eigen::VectorXd theta(4);
  theta << 0.0, 0.3, 1.7, 3.1;
  const auto t = legendre_theta_tables(theta, 3, 0);
  for (int i = 0; i < 4; ++i) {
    const double x = std::cos(theta[i]), s = std::sin(theta[i]);
    EXPECT_NEAR(t[0][0](i, 0), 1.0 / std::sqrt(2.0), 1e-15);
    EXPECT_NEAR(t[0][0](i, 1), std::sqrt(1.5) * x, 1e-15);
    EXPECT_NEAR(t[0][0](i, 2), std::sqrt(2.5) * 0.5 * (3 * x * x - 1), 1e-15);
    EXPECT_NEAR(t[0][1](i, 0), std::sqrt(0.75) * s, 1e-15);
    EXPECT_NEAR(t[0][1](i, 1), std::sqrt(5.0 / 12.0) * 3 * x * s, 1e-15);
    EXPECT_NEAR(t[0][2](i, 0), std::sqrt(5.0 / 48.0) * 3 * s * s, 1e-15);
  }
}

TEST(Legendre, OrthonormalUnderGaussQuadrature) {
  const int L = 128;  // large degree: the recurrence must neither overflow nor lose accuracy
  const auto rule = rbcflow::gauss_legendre(L);
  const auto t = legendre_theta_tables(rule.theta, L, 0);
  double worst = 0.0;
  for (int m : {0, 1, 17, 64, 127}) {
    const Eigen::MatrixXd gram = t[0][m].transpose() * rule.weights.asDiagonal() * t[0][m];
    worst = std::max(worst, (gram - Eigen::MatrixXd::Identity(L - m, L - m)).cwiseAbs().maxCoeff());
  }
  EXPECT_LT(worst, 1e-13);
}

TEST(Legendre, ThetaDerivativesMatchClosedForms) {
  // Pbar_2^0 = sqrt(5/2) (3 cos 2t + 1) / 4 and Pbar_2^2 = sqrt(5/48) 3 (1 - cos 2t) / 2:
  // every theta derivative is a multiple of cos 2t or sin 2t; the poles are not special.
  Eigen::VectorXd theta(5);
  theta << 0.0, 0.01, 1.0, 2.5, 3.14159265358979;
  const auto t = legendre_theta_tables(theta, 3, 4);
  for (int i = 0; i < theta.size(); ++i) {
    const double c2 = std::cos(2 * theta[i]), s2 = std::sin(2 * theta[i]);
    const double k20 = std::sqrt(2.5) * 0.75, k22 = -std::sqrt(5.0 / 48.0) * 1.5;
    const double d20[5] = {k20 * c2 + std::sqrt(2.5) / 4, -2 * k20 * s2, -4 * k20 * c2, 8 * k20 * s2, 16 * k20 * c2};
    const double d22[5] = {k22 * c2 + std::sqrt(5.0 / 48.0) * 1.5, -2 * k22 * s2, -4 * k22 * c2, 8 * k22 * s2, 16 * k22 * c2};
    for (int k = 0; k <= 4; ++k) {
      EXPECT_NEAR(t[k][0](i, 2), d20[k], 1e-13) << "k = " << k << " theta = " << theta[i];
      EXPECT_NEAR(t[k][2](i, 0), d22[k], 1e-13) << "k = " << k << " theta = " << theta[i];
    }
  }
}

// The one-point version (what the tables are built from) in its packed layout, switching between
// orders on one thread (the recurrence coefficients are cached per L): closed forms of
// Pbar_1^1 = sqrt(3/4) sin t and Pbar_2^2 = sqrt(5/48) 3 sin^2 t and their theta derivatives.
TEST(Legendre, OnePointPackedLayoutForEachOrder) {
  for (int L : {3, 17, 3, 40}) {
    for (double theta : {0.0, 0.3, 1.5707963267948966, 2.9, 3.141592653589793}) {
      const int size = rbcflow::legendre_size(L);
      std::vector<double> p(2 * size, -1.0);
      rbcflow::legendre_theta_point(theta, L, 1, p.data());
      const double s = std::sin(theta), c = std::cos(theta);
      const auto at = [&](int k, int n, int m) { return p[k * size + rbcflow::legendre_index(L, n, m)]; };
      EXPECT_NEAR(at(0, 1, 1), std::sqrt(0.75) * s, 1e-15) << "L " << L << " theta " << theta;
      EXPECT_NEAR(at(1, 1, 1), std::sqrt(0.75) * c, 1e-15) << "L " << L << " theta " << theta;
      EXPECT_NEAR(at(0, 2, 2), std::sqrt(5.0 / 48.0) * 3 * s * s, 1e-15) << "L " << L << " theta " << theta;
      EXPECT_NEAR(at(1, 2, 2), std::sqrt(5.0 / 48.0) * 6 * s * c, 1e-14) << "L " << L << " theta " << theta;
    }
  }
}
