#include "geometry/surface/surface_projection.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

TEST(SurfaceProjection, OntoSphereIsRadial) {
  const SHSurface s = make_sphere(8, 1.3);
  const Eigen::Vector3d x0(0.3, -0.9, 1.2);
  const SurfaceProjection p = project_onto_surface(s.coeffs(), x0, 0.5, 4.0);
  ASSERT_TRUE(p.converged);
  EXPECT_LT((p.point - 1.3 * x0.normalized()).norm(), 1e-12);
  EXPECT_NEAR(p.signed_distance, x0.norm() - 1.3, 1e-12);
  const SurfaceProjection inside = project_onto_surface(s.coeffs(), 0.5 * x0, 0.7, 4.5);
  EXPECT_NEAR(inside.signed_distance, 0.5 * x0.norm() - 1.3, 1e-12);
}

TEST(SurfaceProjection, RecoversPointsOffsetAlongTheNormal) {
  // x0 = x(t, p) + d n(t, p) projects back to (t, p) at distance d, on the red cell,
  // including points above the grid's pole (the cell's dimple).
  const int N = 16;
  const SHSurface s = make_biconcave(N);
  for (auto [t, ph] : {std::pair{0.3, 1.0}, {1.4, 2.5}, {1.0e-9, 0.0}, {2.8, 5.0}, {1.6, 0.1}}) {
    const Eigen::Vector3d x = sh_evaluate(s.coeffs(), t, ph).transpose();
    const Eigen::Vector3d a1 = sh_evaluate(s.coeffs(), t, ph, 1, 0).transpose();
    const Eigen::Vector3d a2 = sh_evaluate(s.coeffs(), t, ph, 0, 1).transpose();
    const Eigen::Vector3d n = t < 1e-6 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(a1.cross(a2).normalized());
    for (double d : {0.1, 0.01, -0.05}) {
      const SurfaceProjection p = project_onto_surface(s.coeffs(), x + d * n, t + 0.2, ph - 0.3);
      EXPECT_TRUE(p.converged);
      EXPECT_NEAR(p.signed_distance, d, 1e-10) << "theta " << t << " d " << d;
      EXPECT_LT((p.point - x).norm(), 1e-8) << "theta " << t << " d " << d;
    }
  }
}

// Newton converges quadratically, also off the surface where Gauss-Newton is only linear (rate
// ~ distance x curvature): from a seed 0.3 rad away, points up to 0.4 off the red cell (the
// near-target distances of the quadrature) are projected to round-off in a few iterations.
TEST(SurfaceProjection, ConvergesInAFewNewtonIterations) {
  const SHSurface s = make_biconcave(16);
  for (auto [t, ph] : {std::pair{0.4, 1.0}, {1.5, 2.5}, {2.6, 5.0}}) {
    const SHJet j = sh_evaluate_jet(s.coeffs(), t, ph);
    const Eigen::Vector3d n = j.x_t.cross(j.x_p).normalized();
    for (double d : {0.4, -0.2, 0.05}) {
      const SurfaceProjection p = project_onto_surface(s.coeffs(), j.x + d * n, t + 0.2, ph - 0.2);
      EXPECT_TRUE(p.converged);
      EXPECT_NEAR(p.signed_distance, d, 1e-10) << "theta " << t << " d " << d;
      EXPECT_LE(p.iterations, 10) << "theta " << t << " d " << d;
    }
  }
}
