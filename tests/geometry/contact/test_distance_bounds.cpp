#include "geometry/contact/distance_bounds.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

// A red cell's triangulation (N = 16, as the placement's check mesh): at points around it and
// beyond the table, the bound never exceeds the signed distance measured by a closest-point
// query (sign from the closest triangle's normal, as the overlap tests take it), and inside the
// table it is below it by at most the node spacing times sqrt(3) (twice the farthest a point
// is from its nearest node), plus the single-precision rounding of the node values.
TEST(DistanceBounds, BoundTheSignedDistanceFromBelowWithinTheSpacing) {
  const SHSurface rbc = make_biconcave(16);
  const TriangleMesh mesh = rbc.triangulate(SHTransform(16, SphGrid::gauss(16, 32), 0));
  Eigen::Matrix<double, Eigen::Dynamic, 3> normals(mesh.num_triangles(), 3);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d p0 = mesh.points.row(mesh.triangles(t, 0)).transpose();
    normals.row(t) = (mesh.points.row(mesh.triangles(t, 1)).transpose() - p0)
                         .cross(mesh.points.row(mesh.triangles(t, 2)).transpose() - p0)
                         .transpose();
  }
  const TriangleAabbTree tree(mesh);
  const double margin = 0.3, spacing = 0.05;
  const DistanceBounds bounds(mesh, normals, tree, margin, spacing);
  const Eigen::Vector3d low = mesh.points.colwise().minCoeff().transpose();
  const Eigen::Vector3d high = mesh.points.colwise().maxCoeff().transpose();
  std::mt19937_64 rng(3);
  int inside = 0, in_table = 0, beyond = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Eigen::Vector3d y;
    for (int k = 0; k < 3; ++k) y[k] = std::uniform_real_distribution<double>(low[k] - 0.6, high[k] + 0.6)(rng);
    const TriangleAabbTree::ClosestPoint c = tree.closest_point(y);
    const double sd = (y - c.point).dot(normals.row(c.triangle).transpose()) >= 0 ? c.distance : -c.distance;
    const double lower = bounds.lower(y);
    ASSERT_LE(lower, sd) << "at " << y.transpose();
    const bool table = ((y - low).array() >= -margin).all() && ((y - high).array() <= margin).all();
    if (table) {
      EXPECT_LE(sd - lower, spacing * std::sqrt(3.0) + 1e-6) << "at " << y.transpose();
      ++in_table;
    } else {
      ++beyond;
    }
    inside += sd < 0;
  }
  EXPECT_GT(inside, 500);  // the bounds are tested inside the cell too
  EXPECT_GT(in_table, 5000);
  EXPECT_GT(beyond, 5000);
}
