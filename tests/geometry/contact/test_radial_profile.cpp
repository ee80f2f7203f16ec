// The radial volume-fraction profile (geometry/contact/radial_profile.h) of a sphere on the axis
// of a tube against the exact fraction of each annulus [r1, r2) inside it, over a period L:
//   (4/3) ((rho^2 - r1^2)^(3/2) - (rho^2 - r2^2)^(3/2)) / ((r2^2 - r1^2) L),  r < rho.
// The sphere is moved several periods along the tube and crosses the period's start, as cells
// do in a run. The sum of the fractions times the annuli's volumes is the sphere's volume.
#include "geometry/contact/radial_profile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

TEST(RadialProfile, SphereOnTheAxisOfATube) {
  const double rho = 1.0, R = 1.5, L = 4.0, pi = std::numbers::pi;
  SHSurface sphere = make_sphere(16, rho);
  sphere.translate(Eigen::Vector3d(2.0, 2.0, 0.2 + 3 * L));
  const TriangleMesh mesh = sphere.triangulate(SHTransform(16, SphGrid::gauss(48, 96), 0));
  const Eigen::VectorXi one = Eigen::VectorXi::Zero(mesh.num_points());
  RadialProfileSpec spec{Eigen::Vector3d(2.0, 2.0, 0.0), 2, R, L, 6, 0.04};
  const std::vector<double> f = radial_volume_fraction(mesh, one, spec);
  ASSERT_EQ(f.size(), 6u);
  auto cap = [&](double r) { return r < rho ? std::pow(rho * rho - r * r, 1.5) : 0.0; };
  double volume = 0.0, worst = 0.0;
  for (int i = 0; i < 6; ++i) {
    const double r1 = 0.25 * i, r2 = 0.25 * (i + 1), shell = pi * (r2 * r2 - r1 * r1) * L;
    const double exact = 4.0 / 3.0 * pi * (cap(r1) - cap(r2)) / shell;
    std::printf("[%.2f, %.2f): %.5f, exact %.5f\n", r1, r2, f[i], exact);
    worst = std::max(worst, std::abs(f[i] - exact));
    volume += f[i] * shell;
  }
  std::printf("largest error %.2e; volume %.5f, exact %.5f\n", worst, volume, 4.0 / 3.0 * pi);
  EXPECT_LT(worst, 0.01);
  EXPECT_NEAR(volume / (4.0 / 3.0 * pi), 1.0, 0.01);
  EXPECT_THROW(radial_volume_fraction(mesh, Eigen::VectorXi::Zero(3), spec), std::invalid_argument);
}
