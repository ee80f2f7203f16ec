#include "geometry/surface/surface_projection.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include "geometry/sph/sph_transform.h"
#include "geometry/surface/parachute_fold.h"
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

// On a folded cell (the parachute of a red cell in a D = 1.2 tube, N = 12: the rim's two sheets
// a few grid spacings apart) a Newton step from a grid node can land on another sheet. Points
// within 0.06 of the surface along its normal (the collision band), seeded at the nearest grid
// node and given the 6 iterations of collision removal: the foot point is never farther than
// the seed (each step keeps the distance from growing), so the distance found is at most the
// seed node's. Full steps found distances up to 0.60 here, 0.48 beyond the seed node's.
TEST(SurfaceProjection, NeverEndsFartherThanItsSeed) {
  const int N = 12;
  const SHSurface s = fold_into_parachute(make_biconcave(N), 0.6).surface;
  const SHTransform t = SHTransform::gauss(N);
  const Eigen::MatrixXd nodes = t.synthesize(s.coeffs());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  double worst_excess = -1, largest = 0;
  for (int k = 0; k < 5000; ++k) {
    const double theta = std::acos(1 - 2 * uniform(random)), phi = 2 * std::numbers::pi * uniform(random);
    const SHJet j = sh_evaluate_jet(s.coeffs(), theta, phi);
    const Eigen::Vector3d x0 = j.x + (0.12 * uniform(random) - 0.06) * j.x_t.cross(j.x_p).normalized();
    Eigen::Index seed = 0;
    const double seed_distance = std::sqrt((nodes.rowwise() - x0.transpose()).rowwise().squaredNorm().minCoeff(&seed));
    const int i = static_cast<int>(seed) / t.grid().n_phi(), m = static_cast<int>(seed) % t.grid().n_phi();
    const SurfaceProjection p = project_onto_surface(s.coeffs(), x0, t.grid().theta()[i], t.grid().phi(m), 6);
    worst_excess = std::max(worst_excess, p.distance - seed_distance);
    largest = std::max(largest, p.distance);
  }
  std::printf("largest distance found %.4f, largest excess over the seed's %.2e\n", largest, worst_excess);
  EXPECT_LE(worst_excess, 1e-12);
}
