#pragma once
// Bounds on the signed distance from a body's surface (positive outside), tabulated once on a
// regular grid around it, so that most points of a hard-body test need no closest-point query.
// The signed distance is 1-Lipschitz, so at any point y with nearest grid node c
//   sd(c) - |y - c|  <=  sd(y)  <=  sd(c) + |y - c|,
// and beyond the grid (the body's bounding box widened by `margin`) sd(y) is at least the
// distance to the bounding box. Node values are measured as the tests measure (the closest
// point of the triangulation, the side from its triangle's normal) and stored in single
// precision, rounded down for the lower bound.
#include <Eigen/Core>
#include <vector>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/surface/triangle_mesh.h"

namespace rbcflow {

class DistanceBounds {
 public:
  // `normals`: one per triangle of `mesh`, outward (any length); `spacing`: of the grid.
  DistanceBounds(const TriangleMesh& mesh, const Eigen::Matrix<double, Eigen::Dynamic, 3>& normals,
                 const TriangleAabbTree& tree, double margin, double spacing);
  // A lower bound on the signed distance of y from the surface.
  double lower(const Eigen::Vector3d& y) const;

 private:
  Eigen::Vector3d box_low_, box_high_;  // the surface's bounding box
  Eigen::Vector3d low_;                 // the grid's first node
  Eigen::Vector3i count_;               // nodes per direction
  double spacing_;
  std::vector<float> values_;           // sd at the nodes rounded down, x fastest
};

}  // namespace rbcflow
