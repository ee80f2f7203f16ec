#include "geometry/cgal/aabb_tree.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>

#include <stdexcept>
#include <vector>

namespace rbcflow {
namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Triangle = Kernel::Triangle_3;
using Iterator = std::vector<Triangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, Iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;

Point to_point(const Eigen::Vector3d& v) { return Point(v.x(), v.y(), v.z()); }

}  // namespace

struct TriangleAabbTree::Impl {
  std::vector<Triangle> triangles;
  Tree tree;
};

TriangleAabbTree::TriangleAabbTree(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  if (mesh.num_triangles() == 0) throw std::invalid_argument("TriangleAabbTree: empty mesh");
  impl_->triangles.reserve(mesh.num_triangles());
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    impl_->triangles.emplace_back(to_point(mesh.points.row(mesh.triangles(t, 0))),
                                  to_point(mesh.points.row(mesh.triangles(t, 1))),
                                  to_point(mesh.points.row(mesh.triangles(t, 2))));
  }
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.accelerate_distance_queries();
}

TriangleAabbTree::~TriangleAabbTree() = default;
TriangleAabbTree::TriangleAabbTree(TriangleAabbTree&&) noexcept = default;
TriangleAabbTree& TriangleAabbTree::operator=(TriangleAabbTree&&) noexcept = default;

TriangleAabbTree::ClosestPoint TriangleAabbTree::closest_point(const Eigen::Vector3d& query) const {
  const Point q = to_point(query);
  const auto [p, id] = impl_->tree.closest_point_and_primitive(q);
  ClosestPoint c;
  c.point = Eigen::Vector3d(p.x(), p.y(), p.z());
  c.triangle = static_cast<int>(id - impl_->triangles.cbegin());
  c.distance = (c.point - query).norm();
  return c;
}

double TriangleAabbTree::squared_distance(const Eigen::Vector3d& query) const {
  return impl_->tree.squared_distance(to_point(query));
}

bool TriangleAabbTree::any_within(const Eigen::Vector3d& query, double radius) const {
  const CGAL::Bbox_3 box(query.x() - radius, query.y() - radius, query.z() - radius,
                         query.x() + radius, query.y() + radius, query.z() + radius);
  return impl_->tree.do_intersect(box) && squared_distance(query) <= radius * radius;
}

}  // namespace rbcflow
