#pragma once
// Vessel walls built with gmsh (OpenCASCADE kernel): linear triangles of a target size, normals
// into the lumen (vessel_mesh.h). A vessel along a box axis spans the whole box side and is
// meshed periodically (gmsh setPeriodic on the two end circles): its seam nodes are merged, so
// the wall closes on itself through the box. Every builder returns a mesh that passed
// check_mesh; gmsh errors become std::runtime_error. gmsh stays inside library rbcflow_vessel
// (gmsh::initialize() sets the OpenMP thread count to 1; the builders restore it).
#include <Eigen/Core>
#include <array>
#include <string>

#include "geometry/vessel/vessel_mesh.h"

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

// A parent tube (tube.diameter D) that splits at `centre` along the axis into two daughters,
// which leave at +-angle_deg / 2 to the axis in the plane of the axis and the first frame
// direction (x for a z axis), turn parallel to the axis and merge back into the parent half a
// box length later (wrapped through the box): one period is a parent half and a two-daughter
// loop half, so the wall closes through the box faces like the tube. Parent and daughters
// meet in spheres of the parent's radius at the split and merge points; daughter diameters
// must be below D. Layout in docs/walls.md. A fillet_radius > 0 rounds every edge where parent
// and daughters meet (the flow divider's ridge and the creases around it) with OpenCASCADE's
// fillet of that radius; 0 leaves them sharp.
struct BifurcationSpec {
  TubeSpec tube;  // the parent
  std::array<double, 2> daughter_diameters{};
  double angle_deg = 0.0;      // between the two daughters
  double centre = 0.0;         // the split, along the axis from the box face
  double fillet_radius = 0.0;  // below the smaller daughter's radius
};
VesselMesh bifurcation(const BifurcationSpec& spec);

// The daughters' centrelines: straight at +-angle / 2 for `straight[i]`, a circular arc of
// radius `bend_radius[i]` to the axis direction, `parallel[i]` along it at the lateral
// `offset` from the parent's axis, then the mirror image back to the merge point. Throws
// std::invalid_argument (naming the value and what it needs) when the loop does not fit the box.
struct BifurcationLayout {
  double offset = 0.0;  // max(r1, r2) + (r1 + r2) / 4: a gap of (r1 + r2) / 2 between daughters
  std::array<double, 2> straight{}, bend_radius{}, parallel{};
};
BifurcationLayout bifurcation_layout(const BifurcationSpec& spec);

// A surface mesh file read by gmsh (.msh, .stl, ...), its triangles kept as given (duplicate
// STL nodes merged) but for scaling by `scale` and a whole-surface flip where every normal
// points out of the lumen; `period` as in VesselMesh: nodes that coincide modulo the period (a
// seam written twice) are merged. Throws for an unreadable file or a bad mesh.
VesselMesh read_vessel(const std::string& path, const Eigen::Vector3d& period = Eigen::Vector3d::Zero(),
                       double scale = 1.0);

// A CAD vessel (.step/.stp, .iges/.igs) imported by OpenCASCADE, scaled by `scale` (STEP
// lengths as OpenCASCADE reads them: millimetres), its faces meshed with triangles of the target
// size. Its surface must span the box along `axis` (from 0 to the box side, the box-face cuts
// matching): faces flat in the two box faces (end caps of a solid) are dropped and the end
// curves meshed periodically, as for the tube.
struct VesselFileSpec {
  std::string path;
  double scale = 1.0;
  int axis = 2;
  Eigen::Vector3d box = Eigen::Vector3d::Zero();
  double element_size = 0.0;
};
VesselMesh import_cad_vessel(const VesselFileSpec& spec);

// The vessel of a case's `file` kind: .step/.stp/.iges/.igs by import_cad_vessel, other
// extensions (.msh, .stl) by read_vessel, periodic along `axis` with the box side as period.
VesselMesh vessel_file(const VesselFileSpec& spec);

// Writes the triangles by gmsh; the format follows the extension (.msh, .stl).
void write_vessel(const VesselMesh& wall, const std::string& path);

}  // namespace rbcflow
