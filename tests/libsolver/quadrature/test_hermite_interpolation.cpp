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
      interp.interpolate(data, interp.stencil(t, p), v);
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
  interp.interpolate(data, interp.stencil(5 * dtheta, 0.0), v);
  EXPECT_NEAR(v[0], sh_evaluate(c, 5 * dtheta, 0.0)[0], 1e-14);
}
