#pragma once
// Checks a vessel wall before any solve: a bad mesh is a std::runtime_error naming the problem
// (empty mesh, bad index, degenerate triangle, duplicate nodes, a hole, a non-manifold edge,
// inconsistent orientation), never a crash later in the solver.
#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

struct MeshQuality {
  double min_angle_deg = 0.0;  // smallest triangle angle
  double min_edge = 0.0, max_edge = 0.0;
  double area = 0.0;
  // The largest angle between the normals of two triangles sharing an edge: ~h / R on a smooth
  // wall of curvature radius R, the crease's angle where the surface has one.
  double max_fold_deg = 0.0;
};

// Every edge must be shared by exactly two triangles, traversed in opposite directions (a closed
// orientable surface, closed through the box for a periodic wall); nodes closer than 1e-10 of
// the mesh's extent (modulo the periods) are duplicates.
MeshQuality check_mesh(const VesselMesh& wall);

}  // namespace rbcflow
