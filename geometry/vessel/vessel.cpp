#include "geometry/vessel/vessel.h"

#include <gmsh.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vessel/vessel_periodic.h"

namespace rbcflow {

namespace {

VesselMesh build_tube(const TubeSpec& spec) {
  const Eigen::Vector2d c = frame_centre(spec);
  const int circle = gmsh::model::occ::addCircle(c[0], c[1], 0.0, 0.5 * spec.diameter);
  std::vector<std::pair<int, int>> out;
  gmsh::model::occ::extrude({{1, circle}}, 0, 0, spec.box[spec.axis], out);
  return mesh_periodic_wall(spec.axis, spec.box, spec.element_size);
}

VesselMesh build_constriction(const ConstrictionSpec& spec) {
  const Eigen::Vector2d c = frame_centre(spec.tube);
  const double length = spec.tube.box[spec.tube.axis];
  constexpr int n = 201;
  std::vector<int> points;
  for (int i = 0; i < n; ++i) {
    const double z = length * i / (n - 1);
    points.push_back(gmsh::model::occ::addPoint(c[0] + 0.5 * spec.diameter(z), c[1], z));
  }
  const int spline = gmsh::model::occ::addSpline(points);
  std::vector<std::pair<int, int>> out, interior;
  gmsh::model::occ::revolve({{1, spline}}, c[0], c[1], 0, 0, 0, 1, 2 * std::numbers::pi, out);
  for (int i = 1; i + 1 < n; ++i) interior.emplace_back(0, points[i]);
  gmsh::model::occ::remove(interior);
  return mesh_periodic_wall(spec.tube.axis, spec.tube.box, spec.tube.element_size);
}

}  // namespace

VesselMesh tube(const TubeSpec& spec) {
  validate_tube(spec);
  return with_gmsh("the tube", [&] { return build_tube(spec); });
}

VesselMesh constriction(const ConstrictionSpec& spec) {
  validate_tube(spec.tube);
  if (!(spec.depth >= 0 && spec.depth < spec.tube.diameter) || !(spec.width > 0))
    throw std::invalid_argument("constriction depth must be in [0, D) and width positive");
  return with_gmsh("the constriction", [&] { return build_constriction(spec); });
}

double ConstrictionSpec::diameter(double z) const {
  return tube.diameter - depth * std::exp(-width * (z - centre) * (z - centre));
}

}  // namespace rbcflow
