#pragma once
// A vessel wall: linear triangles, possibly periodic through the box.
//
// Orientation convention (docs/walls.md): the triangle normal (p1 - p0) x (p2 - p0) points
// INTO THE LUMEN, the fluid the vessel carries (towards the axis of a tube). The wall force
// density f of eq. (7)-(8) enters only through the single layer, so this choice fixes no
// sign there; it matters for placing cells (inside = the side the normals point to).
//
// A wall periodic along a box axis has `period[d]` = the box side (0 = not periodic): its
// nodes are unique modulo the period (the seam nodes of the two ends are one node) and a
// triangle crossing the box face is unwrapped by the minimum image (triangle_vertices).
#include <Eigen/Core>

#include "geometry/surface/triangle_mesh.h"

namespace rbcflow {

struct VesselMesh {
  TriangleMesh surface;
  Eigen::Vector3d period = Eigen::Vector3d::Zero();
};

// The shortest image of d under the periods (components with period 0 are left alone).
Eigen::Vector3d minimum_image(const Eigen::Vector3d& d, const Eigen::Vector3d& period);

// The three vertices of triangle t as columns, unwrapped next to the first one.
Eigen::Matrix3d triangle_vertices(const VesselMesh& wall, int t);

// The triangles for drawing (ParaView): each triangle unwrapped as triangle_vertices does, the
// nodes of a triangle that crosses the box face copied to the far side, so that no triangle
// spans the box. Not periodic: for output only.
TriangleMesh drawable_surface(const VesselMesh& wall);

}  // namespace rbcflow
