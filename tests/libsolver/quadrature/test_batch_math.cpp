// The vectorised transcendental functions of the correction builds against the scalar ones of
// <cmath>: glibc documents libmvec's functions to 4 ulp, so atan2 and acos must agree to
// 4 DBL_EPSILON relative (the scalar ones are within 1 ulp of exact). The mask composes two
// exponentials, exp(2 e^{-1/t} / (t - 1)), whose exponent reaches -10^3 before eta underflows,
// so its relative error grows with it; as a weight in [0, 1] it must agree to 1e-14
// absolutely, far below any quadrature error it feeds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <numbers>
#include <vector>

#include "libsolver/quadrature/batch_math.h"
#include "libsolver/quadrature/polar_patch.h"

using namespace rbcflow;

TEST(BatchMath, Atan2MatchesTheScalarFunctionInEveryQuadrantAndOnTheAxes) {
  std::vector<double> y, x;
  for (int i = 0; i < 203; ++i) {  // an odd count: the loop's vector remainder is exercised
    const double angle = -std::numbers::pi + 2 * std::numbers::pi * i / 202.0, r = 0.1 + 0.01 * i;
    y.push_back(r * std::sin(angle));
    x.push_back(r * std::cos(angle));
  }
  for (double v : {0.0, 1.0, -1.0}) y.push_back(0.0), x.push_back(v);
  y.push_back(2.0), x.push_back(0.0);
  std::vector<double> out(y.size());
  batch_atan2(y.data(), x.data(), out.data(), y.size());
  for (std::size_t i = 0; i < y.size(); ++i) {
    const double exact = std::atan2(y[i], x[i]);
    EXPECT_NEAR(out[i], exact, 4 * DBL_EPSILON * std::abs(exact)) << "y " << y[i] << " x " << x[i];
  }
}

TEST(BatchMath, AcosMatchesTheScalarFunctionAndClampsToItsDomain) {
  std::vector<double> x;
  for (int i = 0; i <= 201; ++i) x.push_back(-1.0 + 2.0 * i / 201.0);
  x.push_back(1.0 + 1e-15);
  x.push_back(-1.0 - 1e-15);
  std::vector<double> out(x.size());
  batch_acos(x.data(), out.data(), x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double exact = std::acos(std::clamp(x[i], -1.0, 1.0));
    EXPECT_NEAR(out[i], exact, 4 * DBL_EPSILON * exact) << "x " << x[i];
  }
}

TEST(BatchMath, PatchMaskMatchesTheScalarMaskIncludingItsEnds) {
  const double rho1 = 1.3;
  std::vector<double> rho;
  for (int i = 0; i <= 1001; ++i) rho.push_back(1.2 * rho1 * i / 1001.0);
  for (double t : {1e-4, 1e-3, 0.999, 1.0 - 1e-12, 1.0}) rho.push_back(t * rho1);
  std::vector<double> eta(rho.size());
  batch_patch_mask(rho.data(), rho1, eta.data(), rho.size());
  for (std::size_t i = 0; i < rho.size(); ++i) EXPECT_NEAR(eta[i], patch_mask(rho[i], rho1), 1e-14) << "rho " << rho[i];
  EXPECT_EQ(eta[0], 1.0);      // the centre
  EXPECT_EQ(eta.back(), 0.0);  // the rim
}
