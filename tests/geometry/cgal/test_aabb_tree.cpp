#include "geometry/cgal/aabb_tree.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <limits>
#include <random>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

namespace {

// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5).
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                    const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

}  // namespace

TEST(TriangleAabbTree, ClosestPointsEqualBruteForce) {
  const TriangleMesh mesh = make_biconcave(12).triangulate(SHTransform::gauss(12));
  const TriangleAabbTree tree(mesh);
  std::mt19937 gen(4);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int q = 0; q < 200; ++q) {
    const Eigen::Vector3d p(u(gen), u(gen), 0.5 * u(gen));
    double best = std::numeric_limits<double>::max();
    Eigen::Vector3d best_point = Eigen::Vector3d::Zero();
    auto closest_on = [&](int t) {
      return closest_on_triangle(p, mesh.points.row(mesh.triangles(t, 0)), mesh.points.row(mesh.triangles(t, 1)),
                                 mesh.points.row(mesh.triangles(t, 2)));
    };
    for (int t = 0; t < mesh.num_triangles(); ++t) {
      const Eigen::Vector3d c = closest_on(t);
      if ((c - p).norm() < best) {
        best = (c - p).norm();
        best_point = c;
      }
    }
    const auto hit = tree.closest_point(p);
    EXPECT_NEAR(hit.distance, best, 1e-12);
    // The same point (ties are points on a shared edge or vertex, hence equal) on the triangle named.
    EXPECT_LT((hit.point - best_point).norm(), 1e-12);
    EXPECT_LT((closest_on(hit.triangle) - hit.point).norm(), 1e-12);
    EXPECT_NEAR(std::sqrt(tree.squared_distance(p)), best, 1e-12);
    EXPECT_EQ(tree.any_within(p, best * 1.001), true);
    EXPECT_EQ(tree.any_within(p, best * 0.999), false);
  }
}

TEST(TriangleAabbTree, EmptyMeshIsAnError) { EXPECT_THROW(TriangleAabbTree(TriangleMesh{}), std::invalid_argument); }
