#pragma once
// Hard-body tests between cells, each a copy of one of a few bodies (surfaces) turned, scaled
// about its centroid and moved (a pose), in a periodic box and inside an optional vessel wall.
// One AABB tree over each body's grid triangulation serves every pair: the vertices of one cell
// are taken into the other's body frame. Two cells are apart when every vertex of each, and
// every point of its order-N grid (the solver's points, between the vertices), is outside the
// other and at least `gap` from its triangles (both ways round); likewise inside the wall. Cells placed at
// random are copies of one reference; cells listed in a case (each with its own orientation
// and perturbation) are a body each, with the identity pose at their centroid.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/contact/distance_bounds.h"
#include "geometry/surface/sh_surface.h"
#include "geometry/contact/wall_distance.h"

namespace rbcflow {

struct CellPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // of the body's centroid
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  double scale = 1.0;
  int body = 0;  // which of the CellOverlap's bodies
};

class CellOverlap {
 public:
  // `period`: box sides of the periodic directions (0: not periodic); `wall` may be null and
  // must outlive this object.
  CellOverlap(const SHSurface& reference, int check_order, const Eigen::Vector3d& period, const WallDistance* wall,
              double gap);
  // One body per surface (CellPose::body indexes `bodies`).
  CellOverlap(const std::vector<SHSurface>& bodies, int check_order, const Eigen::Vector3d& period,
              const WallDistance* wall, double gap);

  // Of body 0 (the reference): the largest distance of its tested points from its centroid, the
  // centroid, and its triangulation with the centroid at the origin.
  double radius() const { return bodies_[0].radius; }
  const Eigen::Vector3d& centroid() const { return bodies_[0].centroid; }
  const TriangleMesh& mesh() const { return bodies_[0].mesh; }
  // The centroid of body b as given (the position of its identity pose) and its triangulation
  // about it.
  const Eigen::Vector3d& centroid(int b) const { return bodies_[b].centroid; }
  const TriangleMesh& mesh(int b) const { return bodies_[b].mesh; }

  // Whether cell b (every periodic image of it) is apart from cell a. With `same`, a and b are
  // one cell and only its images other than itself are tested.
  bool apart(const CellPose& a, const CellPose& b, bool same = false) const;
  // Whether every vertex of the cell is at least `gap` inside the wall (true without a wall).
  bool inside_wall(const CellPose& a) const;

 private:
  struct Body {
    Body(const SHSurface& surface, int check_order);
    Eigen::Vector3d centroid;
    TriangleMesh mesh;  // the surface's triangulation, centroid at the origin
    Eigen::Matrix<double, Eigen::Dynamic, 3> points;  // tested: mesh's vertices and the order-N grid
    Eigen::Matrix<double, Eigen::Dynamic, 3> normals;
    double radius = 0.0;
    TriangleAabbTree tree;
    // Of the reference of random placement (every cell a copy of it): its signed distance
    // tabulated, so that a tested point clearly apart needs no query. Listed cells (a body
    // each, tested a few times) have none.
    std::optional<DistanceBounds> bounds;
  };
  bool vertices_apart(const CellPose& a, const CellPose& b, const Eigen::Vector3d& shift) const;

  Eigen::Vector3d period_;
  const WallDistance* wall_;
  double gap_;
  std::vector<Body> bodies_;
};

}  // namespace rbcflow
