#pragma once
// Signed distance from points to a vessel wall, positive in the lumen (the side the wall
// normals point to, vessel_mesh.h), by a CGAL AABB tree over the wall triangles. The side is
// that of the pseudonormal at the closest point (Baerentzen & Aanaes, IEEE TVCG 11, 2005): the
// triangle's normal inside it, the sum of the two triangles' normals on an edge, the
// angle-weighted normal at a node; a triangle's own normal would put points beside a ridge
// that juts into the lumen (the divider between two branches) on the wrong side. A wall periodic
// along box axes is unwrapped and copied once to each side along those axes, and queries are
// wrapped into the box first, so that points anywhere (cells are not wrapped) get the distance
// to the nearest periodic image of the wall.
#include <Eigen/Core>
#include <vector>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

class WallDistance {
 public:
  explicit WallDistance(const VesselMesh& wall);

  struct Query {
    Eigen::Vector3d point;         // closest wall point (the image next to the query)
    Eigen::Vector3d normal;        // the unit pseudonormal there, into the lumen
    double signed_distance = 0.0;  // > 0 in the lumen, < 0 beyond the wall
  };
  Query closest(const Eigen::Vector3d& x) const;

  const Eigen::Vector3d& period() const { return period_; }

 private:
  // The pseudonormal at the point with barycentric coordinates `b` of wall triangle t.
  Eigen::Vector3d pseudonormal(int t, const Eigen::Vector3d& b) const;

  Eigen::Vector3d period_;
  Eigen::Matrix<int, Eigen::Dynamic, 3> triangles_;           // the wall's, node indices
  Eigen::Matrix<double, Eigen::Dynamic, 3> face_normals_;     // unit, per wall triangle
  Eigen::Matrix<double, Eigen::Dynamic, 3> node_normals_;     // angle-weighted, per wall node
  Eigen::Matrix<double, Eigen::Dynamic, 3> edge_normals_;     // per triangle edge a (opposite node a): the sum of its two faces'
  TriangleMesh images_;  // unwrapped triangles and their periodic copies (wall triangle = index % count)
  TriangleAabbTree tree_;
};

// The smallest signed distance from `wall` of the points of any of the sets (each cell's grid
// points): how close the cells come to the wall (negative: through it). A set whose centre is
// farther from the wall than the smallest so far plus the set's radius is skipped, and so is a
// point within that margin of the last point queried (the ball about a point at distance d from
// the wall holds no wall): the same minimum with few queries. +infinity without points.
double smallest_wall_distance(const WallDistance& wall, const std::vector<Eigen::MatrixX3d>& point_sets);

// Volume of the lumen enclosed by `wall` (one period along its periodic axes): the divergence
// theorem with the field x_k / K over the K non-periodic axes k, whose flux through the cut
// faces at the box ends vanishes. Throws when the wall is periodic along all three axes.
double lumen_volume(const VesselMesh& wall);

}  // namespace rbcflow
