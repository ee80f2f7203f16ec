#include <gtest/gtest.h>

#include <numbers>

#include "geometry/reference_shapes.h"
#include "libsolver/spme/double_layer_linear.h"
#include "test_points.h"

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;
}

// A uniform density psi = e_j on a closed surface: -(8 pi/V) integral n_j (x - x0)_i dS
// = -8 pi (V_S / V) delta_ij at every target (REFERENCES.md section 1), wherever the surface is.
TEST(DoubleLayerLinear, UniformDensityGivesMinusEightPiVolumeFraction) {
  const int N = 12;
  const PeriodicBox box(Eigen::Vector3d(1.0, 1.2, 0.9));
  const PointField targets = test::random_points(7, Eigen::Vector3d(3.0, 3.0, 3.0), 1);
  for (const Eigen::Vector3d& centre :
       {Eigen::Vector3d(0.5, 0.5, 0.5), Eigen::Vector3d(-4.0, 2.2, 0.95)}) {
    SHSurface ellipsoid = make_ellipsoid(N, Eigen::Vector3d(0.3, 0.2, 0.25));
    ellipsoid.translate(centre);
    const SurfaceGeometry g = ellipsoid.geometry(SHTransform::gauss(N));
    const double fraction = enclosed_volume(g) / box.volume();
    for (int j = 0; j < 3; ++j) {
      const PointField q = g.area_weight * Eigen::RowVector3d::Unit(j);
      const PointField u = double_layer_linear_part(box, g.x, q, g.normal, targets);
      for (int t = 0; t < targets.rows(); ++t)
        EXPECT_LT((u.row(t) + 8 * pi * fraction * Eigen::RowVector3d::Unit(j)).norm(), 1e-12);
    }
  }
}

// For a general density the result is -(8 pi/V)(M - c x0), M = sum (q.n) x, c = sum q.n.
TEST(DoubleLayerLinear, PointFormula) {
  const PeriodicBox box(Eigen::Vector3d(2.0, 1.0, 1.0));
  const PointField xs = test::random_points(5, Eigen::Vector3d::Ones(), 2),
                   xt = test::random_points(3, Eigen::Vector3d::Ones(), 3);
  const PointField q = test::random_vectors(5, 4), n = test::random_vectors(5, 5);
  const PointField u = double_layer_linear_part(box, xs, q, n, xt);
  for (int t = 0; t < 3; ++t) {
    Eigen::RowVector3d expected = Eigen::RowVector3d::Zero();
    for (int s = 0; s < 5; ++s) expected += q.row(s).dot(n.row(s)) * (xs.row(s) - xt.row(t));
    expected *= -8 * pi / 2.0;
    EXPECT_LT((u.row(t) - expected).norm(), 1e-13);
  }
  EXPECT_THROW(double_layer_linear_part(box, xs, q.topRows(4), n, xt), std::invalid_argument);
}
