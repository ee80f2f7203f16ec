#include "libsolver/quadrature/hermite_interpolation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace rbcflow;

TEST(HermiteInterpolation, ConvergesAtFourthOrderEverywhereIncludingThePoles) {
  // A fixed band-limited field interpolated on grids of refinement r: error ~ r^-4.
  const int N = 10;
  SHCoeffs c(N, 2);
  std::mt19937 gen(2);
  std::normal_distribution<double> nd;
  for (Eigen::Index i = 0; i < c.values().size(); ++i) c.values().data()[i] = nd(gen);
  std::uniform_real_distribution<double> ut(0.0, 3.14159265358979), up(0.0, 6.2831853);
  std::vector<std::pair<double, double>> pts = {{0.0, 1.0}, {1e-6, 2.0}, {3.14159265358979, 0.3}};
  for (int k = 0; k < 200; ++k) pts.emplace_back(ut(gen), up(gen));
  double prev = 0.0;
  std::printf("  refinement  max error\n");
  for (int r : {2, 4, 8}) {
    const HermiteInterpolator interp(N, r);
    const HermiteData data = interp.node_data(c);
    double err = 0.0;
    for (auto [t, p] : pts) {
      Eigen::Vector2d v;
      interp.interpolate<2>(data, interp.stencil(t, p), v);
      err = std::max(err, (v - sh_evaluate(c, t, p).transpose()).cwiseAbs().maxCoeff());
    }
    std::printf("  %2d          %.3e\n", r, err);
    if (prev > 0) {
      EXPECT_GT(prev / err, 12.0);  // 2^4 = 16
    }
    prev = err;
  }
}

TEST(HermiteInterpolation, ReproducesNodeValues) {
  SHCoeffs c(6, 1);
  c.a(3, 2) = 1.0;
  const HermiteInterpolator interp(6, 2);
  const HermiteData data = interp.node_data(c);
  Eigen::Matrix<double, 1, 1> v;
  const double dtheta = 3.14159265358979323846 / (interp.n_theta() - 1);
  interp.interpolate<1>(data, interp.stencil(5 * dtheta, 0.0), v);
  EXPECT_NEAR(v[0], sh_evaluate(c, 5 * dtheta, 0.0)[0], 1e-14);
}

TEST(HermiteInterpolation, PhiShiftMovesTheStencilByWholeCells) {
  // The corrections of a ring of grid nodes share one stencil table, shifted in phi: the
  // shifted stencil must interpolate at phi + shift * dphi, across the seam phi = 2 pi too.
  SHCoeffs c(8, 1);
  c.a(5, 3) = 1.0;
  c.b(2, 1) = 0.5;
  const HermiteInterpolator interp(8, 2);
  const HermiteData data = interp.node_data(c);
  const double dphi = 2 * 3.14159265358979323846 / interp.n_phi();
  for (int shift : {1, 7, interp.n_phi() - 1}) {
    const double theta = 1.1, phi = 5.9;
    Eigen::Matrix<double, 1, 1> shifted, direct;
    interp.interpolate<1>(data, interp.stencil(theta, phi), shifted, shift);
    interp.interpolate<1>(data, interp.stencil(theta, phi + shift * dphi), direct);
    EXPECT_NEAR(shifted[0], direct[0], 1e-13) << "shift " << shift;
  }
}
