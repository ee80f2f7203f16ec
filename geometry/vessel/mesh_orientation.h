#pragma once
// Orienting a wall mesh by the convention of vessel_mesh.h: normals into the lumen. gmsh meshes
// each CAD face in its own parametric direction, so a wall made of several faces (a fused
// bifurcation, an imported STEP solid) comes out with mixed normals; these functions make them
// agree without changing any triangle's shape.
#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

// sum over triangles of A n . (c - x0), with n the unit normal, c the centroid and x0 the
// first node; components along periodic axes are dropped from c - x0. By the divergence
// theorem (the field c - x0 has divergence 3, or 3 minus the number of periodic axes, and
// is constant along a period) this is -(that divergence) x (enclosed volume) for normals into
// the lumen, + for normals out of it. Exact on the polyhedron.
double lumen_flux(const VesselMesh& wall);

// Flips triangles so that each edge shared by two triangles is traversed in opposite
// directions (breadth-first over edges), then flips each connected piece whose lumen_flux is
// positive. Edges in more than two triangles are left for check_mesh to report.
void orient_into_lumen(VesselMesh& wall);

}  // namespace rbcflow
