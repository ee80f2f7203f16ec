// CAD vessels through OpenCASCADE: import, scale, drop the end caps, mesh periodically; and
// the choice between CAD and mesh files by extension.
#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vessel/vessel.h"
#include "geometry/vessel/vessel_periodic.h"
#include "geometry/format_number.h"

namespace rbcflow {

namespace {

VesselMesh build_cad_vessel(const VesselFileSpec& spec) {
  namespace occ = gmsh::model::occ;
  std::vector<std::pair<int, int>> shapes;
  try {
    occ::importShapes(spec.path, shapes);
  } catch (...) {
    throw std::runtime_error("cannot read CAD file " + spec.path + ": " + gmsh_last_error());
  }
  if (shapes.empty()) throw std::runtime_error("CAD file " + spec.path + " has no shapes");
  if (spec.scale != 1.0) occ::dilate(shapes, 0, 0, 0, spec.scale, spec.scale, spec.scale);
  // Box to frame coordinates: frame k = box frame_axis(axis, k) (vessel_periodic.h).
  std::vector<double> to_frame(12, 0.0);
  for (int k = 0; k < 3; ++k) to_frame[4 * k + frame_axis(spec.axis, k)] = 1.0;
  occ::affineTransform(shapes, to_frame);
  occ::synchronize();

  const double length = spec.box[spec.axis];
  double x0, y0, z0, x1, y1, z1;
  gmsh::model::getBoundingBox(-1, -1, x0, y0, z0, x1, y1, z1);
  const double tolerance = 1e-5 * length;  // OCC pads bounding boxes by its tolerance
  if (std::abs(z0) > tolerance || std::abs(z1 - length) > tolerance)
    throw std::runtime_error("CAD vessel " + spec.path + " spans [" + format_number(z0, 6) + ", " + format_number(z1, 6) + "] along " +
                             std::string(1, "xyz"[spec.axis]) + " (after scale " + format_number(spec.scale, 6) +
                             "); a periodic vessel must span the box side [0, " + format_number(length, 6) + "]");
  std::vector<std::pair<int, int>> faces;
  gmsh::model::getEntities(faces, 2);
  const std::vector<std::pair<int, int>> wall = without_end_caps(faces, length);
  if (wall.empty()) throw std::runtime_error("CAD file " + spec.path + " has no surfaces");
  keep_only_surfaces(wall);
  return mesh_periodic_wall(spec.axis, spec.box, spec.element_size);
}

}  // namespace

VesselMesh import_cad_vessel(const VesselFileSpec& spec) {
  if (!std::filesystem::is_regular_file(spec.path))
    throw std::runtime_error("CAD file " + spec.path + " does not exist");
  if (std::filesystem::file_size(spec.path) == 0) throw std::runtime_error("CAD file " + spec.path + " is empty");
  if (spec.axis < 0 || spec.axis > 2 || !(spec.box.minCoeff() > 0))
    throw std::invalid_argument("CAD vessel needs an axis 0, 1 or 2 and a box with positive sides");
  if (!(spec.element_size > 0)) throw std::invalid_argument("CAD vessel element size must be positive");
  if (!(spec.scale > 0)) throw std::invalid_argument("CAD vessel scale must be positive");
  try {
    return with_gmsh("CAD vessel " + spec.path, [&] { return build_cad_vessel(spec); });
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    if (what.find(spec.path) != std::string::npos) throw;
    throw std::runtime_error("CAD vessel " + spec.path + ": " + what);
  }
}

VesselMesh vessel_file(const VesselFileSpec& spec) {
  std::string ext = std::filesystem::path(spec.path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs") return import_cad_vessel(spec);
  if (spec.axis < 0 || spec.axis > 2) throw std::invalid_argument("vessel axis must be 0, 1 or 2");
  Eigen::Vector3d period = Eigen::Vector3d::Zero();
  period[spec.axis] = spec.box[spec.axis];
  return read_vessel(spec.path, period, spec.scale);
}

}  // namespace rbcflow
