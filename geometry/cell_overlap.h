#pragma once
// Hard-body tests between copies of one reference cell, each turned, scaled about its centroid
// and moved (a pose), in a periodic box and inside an optional vessel wall. One AABB tree over
// the reference's grid triangulation serves every pair: the vertices of one cell are taken
// into the other's body frame. Two cells are apart when every vertex of each is outside the
// other and at least `gap` from its triangles (both ways round).
#include <Eigen/Core>
#include <memory>

#include "aabb_tree.h"
#include "sh_surface.h"
#include "wall_distance.h"

namespace rbcflow {

struct CellPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double scale = 1.0;
};

class CellOverlap {
 public:
  // `period`: box sides of the periodic directions (0: not periodic); `wall` may be null and
  // must outlive this object.
  CellOverlap(const SHSurface& reference, int check_order, const Eigen::Vector3d& period, const WallDistance* wall,
              double gap);

  double radius() const { return radius_; }  // of the reference's vertices about its centroid
  const Eigen::Vector3d& centroid() const { return centroid_; }
  const TriangleMesh& mesh() const { return mesh_; }  // the reference's triangulation, centroid at 0

  // Whether cell b (every periodic image of it) is apart from cell a. With `same`, a and b are
  // one cell and only its images other than itself are tested.
  bool apart(const CellPose& a, const CellPose& b, bool same = false) const;
  // Whether every vertex of the cell is at least `gap` inside the wall (true without a wall).
  bool inside_wall(const CellPose& a) const;

 private:
  bool vertices_apart(const CellPose& a, const CellPose& b, const Eigen::Vector3d& shift) const;

  Eigen::Vector3d period_;
  const WallDistance* wall_;
  double gap_;
  Eigen::Vector3d centroid_;
  TriangleMesh mesh_;  // the reference triangulation, centroid at the origin
  Eigen::Matrix<double, Eigen::Dynamic, 3> normals_;
  double radius_ = 0.0;
  TriangleAabbTree tree_;
};

}  // namespace rbcflow
