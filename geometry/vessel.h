#pragma once
// Vessel walls built with gmsh (OpenCASCADE kernel): linear triangles of a target size, normals
// into the lumen (vessel_mesh.h). A vessel along a box axis spans the whole box side and is
// meshed periodically (gmsh setPeriodic on the two end circles): its seam nodes are merged, so
// the wall closes on itself through the box. Every builder returns a mesh that passed
// check_mesh; gmsh errors become std::runtime_error. gmsh stays inside library rbcflow_vessel
// (gmsh::initialize() sets the OpenMP thread count to 1; the builders restore it).
#include <Eigen/Core>
#include <string>

#include "vessel_mesh.h"

namespace rbcflow {

// A straight tube of the given diameter on the axis `axis` (0, 1, 2) of the box, centred in
// the box's cross-section; its length is the box side along the axis.
struct TubeSpec {
  double diameter = 0.0;
  int axis = 2;
  Eigen::Vector3d box = Eigen::Vector3d::Zero();
  double element_size = 0.0;
};
VesselMesh tube(const TubeSpec& spec);

// A tube of diameter d(z) = D - depth exp(-width (z - centre)^2) (section 10.2), z along the
// axis measured from the box face; the profile is a spline through 201 points.
struct ConstrictionSpec {
  TubeSpec tube;  // D = tube.diameter
  double depth = 0.0, width = 0.0, centre = 0.0;
  double diameter(double z) const;
};
VesselMesh constriction(const ConstrictionSpec& spec);

// A surface mesh file read by gmsh (.msh, .stl, ...), its triangles kept as given (duplicate
// STL nodes merged); `period` as in VesselMesh. Throws for an unreadable file or a bad mesh.
VesselMesh read_vessel(const std::string& path, const Eigen::Vector3d& period = Eigen::Vector3d::Zero());

// Writes the triangles by gmsh; the format follows the extension (.msh, .stl).
void write_vessel(const VesselMesh& wall, const std::string& path);

}  // namespace rbcflow
