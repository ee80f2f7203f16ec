#include <gtest/gtest.h>

#include <numbers>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/spme/double_layer_linear.h"
#include "test_points.h"

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;

// Eq. (3)'s linear part summed as written, -(8 pi/V) sum_s (q_s . n_s) (x_s - x0), at x0.
Eigen::RowVector3d equation_3_sum(const PeriodicBox& box, const PointField& xs, const PointField& q,
                                  const PointField& n, const Eigen::RowVector3d& x0) {
  Eigen::RowVector3d u = Eigen::RowVector3d::Zero();
  for (int s = 0; s < xs.rows(); ++s) u += q.row(s).dot(n.row(s)) * (xs.row(s) - x0);
  return -8 * pi / box.volume() * u;
}
}  // namespace

// A uniform density psi = e_j on a closed surface: -(8 pi/V) integral n_j (x - x0)_i dS
// = -8 pi (V_S / V) delta_ij at every target (docs/references.md section 1), wherever the
// surface is.
TEST(DoubleLayerLinear, UniformDensityGivesMinusEightPiVolumeFraction) {
  const int N = 12;
  const PeriodicBox box(Eigen::Vector3d(1.0, 1.2, 0.9));
  for (const Eigen::Vector3d& centre : {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(-4.0, 2.2, 0.95)}) {
    SHSurface ellipsoid = make_ellipsoid(N, Eigen::Vector3d(0.3, 0.2, 0.25));
    ellipsoid.translate(centre);
    const SurfaceGeometry g = ellipsoid.geometry(SHTransform::gauss(N));
    const double fraction = enclosed_volume(g) / box.volume();
    for (int j = 0; j < 3; ++j) {
      const PointField q = g.area_weight * Eigen::RowVector3d::Unit(j);
      const Eigen::RowVector3d u = double_layer_linear_part(box, g.x, q, g.normal, static_cast<int>(g.x.rows()));
      EXPECT_LT((u + 8 * pi * fraction * Eigen::RowVector3d::Unit(j)).norm(), 1e-12);
    }
  }
}

// Densities without net flux through either surface: eq. (3)'s sum itself, the same at every
// target.
TEST(DoubleLayerLinear, FluxFreeDensitiesGiveEquation3AtEveryTarget) {
  const PeriodicBox box(Eigen::Vector3d(2.0, 1.0, 1.5));
  const int per_surface = 6;
  const PointField xs = test::random_points(2 * per_surface, Eigen::Vector3d::Ones(), 2);
  const PointField n = test::random_vectors(2 * per_surface, 5).rowwise().normalized();
  PointField q = test::random_vectors(2 * per_surface, 4);
  for (int first : {0, per_surface}) {  // remove each surface's flux: q_s -= (Q_S / count) n_s
    const double flux = (q.middleRows(first, per_surface).array() * n.middleRows(first, per_surface).array()).sum();
    q.middleRows(first, per_surface) -= (flux / per_surface) * n.middleRows(first, per_surface);
  }
  const Eigen::RowVector3d u = double_layer_linear_part(box, xs, q, n, per_surface);
  const PointField targets = test::random_points(4, Eigen::Vector3d(5.0, 5.0, 5.0), 3);
  for (int t = 0; t < targets.rows(); ++t) EXPECT_LT((u - equation_3_sum(box, xs, q, n, targets.row(t))).norm(), 1e-13);
}

// With net flux, eq. (3)'s sum grows with the distance between the surface and the target, so
// it would depend on which periodic image holds a surface; the flux term is left out, and
// moving either surface by whole periods changes nothing.
TEST(DoubleLayerLinear, SurfacesMovedByWholePeriodsGiveTheSameTerm) {
  const PeriodicBox box(Eigen::Vector3d(2.0, 1.0, 1.5));
  const int per_surface = 5;
  PointField xs = test::random_points(2 * per_surface, Eigen::Vector3d::Ones(), 6);
  const PointField q = test::random_vectors(2 * per_surface, 7), n = test::random_vectors(2 * per_surface, 8);
  const Eigen::RowVector3d before = double_layer_linear_part(box, xs, q, n, per_surface);
  Eigen::RowVector3d expected = Eigen::RowVector3d::Zero();  // about each surface's node mean
  for (int first : {0, per_surface}) {
    const PointField x = xs.middleRows(first, per_surface);
    const Eigen::RowVector3d centre = x.colwise().mean();
    for (int s = 0; s < per_surface; ++s)
      expected += q.row(first + s).dot(n.row(first + s)) * (x.row(s) - centre);
  }
  EXPECT_LT((before + 8 * pi / box.volume() * expected).norm(), 1e-13);
  xs.bottomRows(per_surface).rowwise() += Eigen::RowVector3d(2 * 2.0, -3 * 1.0, 7 * 1.5);
  EXPECT_LT((double_layer_linear_part(box, xs, q, n, per_surface) - before).norm(), 1e-12);
}

TEST(DoubleLayerLinear, RejectsMismatchedRowsAndPartialSurfaces) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  const PointField xs = test::random_points(6, Eigen::Vector3d::Ones(), 2);
  const PointField q = test::random_vectors(6, 4), n = test::random_vectors(6, 5);
  EXPECT_THROW(double_layer_linear_part(box, xs, q.topRows(4), n, 3), std::invalid_argument);
  EXPECT_THROW(double_layer_linear_part(box, xs, q, n, 4), std::invalid_argument);
  EXPECT_THROW(double_layer_linear_part(box, xs, q, n, 0), std::invalid_argument);
}
