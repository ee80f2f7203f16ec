#pragma once
// Meshing a wall that is periodic along a box axis (internal to rbcflow_vessel; call inside a
// GmshSession). The builders make their OCC model in a frame with the vessel axis along z:
// frame coordinate k is box coordinate frame_axis(axis, k), a cyclic permutation, so the frame
// is right-handed and orientations carry over.
#include <Eigen/Core>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "geometry/vessel/gmsh_session.h"
#include "geometry/vessel/vessel.h"

namespace rbcflow {

int frame_axis(int axis, int k);

// The centre of the box cross-section in frame coordinates (x, y).
Eigen::Vector2d frame_centre(const TubeSpec& s);

// Throws std::invalid_argument naming the bad value (axis, box, diameter, element size).
void validate_tube(const TubeSpec& s);

// Runs `build` in a GmshSession; gmsh's non-standard exceptions become std::runtime_error
// "gmsh could not mesh WHAT: gmsh's last error".
template <class Build>
VesselMesh with_gmsh(const std::string& what, Build build) {
  GmshSession session;
  try {
    return build();
  } catch (const std::exception&) {
    throw;
  } catch (...) {
    throw std::runtime_error("gmsh could not mesh " + what + ": " + gmsh_last_error());
  }
}

// Removes from the OCC model every volume, every surface not in `surfaces` and every curve not
// on their boundary (revolve profiles, cut end faces), so that only the wall gets meshed.
void keep_only_surfaces(const std::vector<std::pair<int, int>>& surfaces);

// The faces but those flat in the frame's box faces z = 0 and z = length (a solid's end caps,
// a cut at the box face): the wall of a vessel that runs through them.
std::vector<std::pair<int, int>> without_end_caps(const std::vector<std::pair<int, int>>& faces, double length);

// Meshes the surfaces of the current OCC model (no volumes), which span the frame's z from 0 to
// box[axis]: every curve in the plane z = 0 gets the curve above it in z = box[axis] as its
// periodic copy (gmsh setPeriodic), so the nodes of the two ends match; those of the far end are
// merged into the near ones. Then maps to box coordinates (z shifted by `shift` along the axis
// and wrapped into the box), orients the normals into the lumen and checks the mesh. With
// grade_short_curves (a filleted model: where fillets meet, OpenCASCADE leaves curves far
// shorter than the element size) the triangles shrink towards such curves instead of becoming
// slivers beside them.
VesselMesh mesh_periodic_wall(int axis, const Eigen::Vector3d& box, double element_size, double shift = 0.0,
                              bool grade_short_curves = false);

}  // namespace rbcflow
