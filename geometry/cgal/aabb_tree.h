#pragma once
// Closest-point and distance queries against a triangle mesh, by a CGAL AABB tree. CGAL stays
// inside this one file pair (it adds -frounding-math to whatever includes it).
#include <Eigen/Core>
#include <memory>

#include "geometry/surface/triangle_mesh.h"

namespace rbcflow {

class TriangleAabbTree {
 public:
  explicit TriangleAabbTree(const TriangleMesh& mesh);
  ~TriangleAabbTree();
  TriangleAabbTree(TriangleAabbTree&&) noexcept;
  TriangleAabbTree& operator=(TriangleAabbTree&&) noexcept;

  struct ClosestPoint {
    Eigen::Vector3d point;  // the closest point on the mesh
    int triangle = -1;      // the triangle it lies on
    double distance = 0.0;
  };
  ClosestPoint closest_point(const Eigen::Vector3d& query) const;
  double squared_distance(const Eigen::Vector3d& query) const;
  // Whether any triangle comes within `radius` of `query` (cheaper than a closest point).
  bool any_within(const Eigen::Vector3d& query, double radius) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rbcflow
