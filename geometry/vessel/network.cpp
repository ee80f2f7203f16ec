// The network builder of network.h: OpenCASCADE cylinders and junction spheres, fused, cut at
// the box faces along the axis and meshed periodically (vessel_periodic.h).
#include "geometry/vessel/network.h"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "geometry/vessel/crease_fillet.h"
#include "geometry/vessel/vessel_periodic.h"

namespace rbcflow {
namespace {

using DimTags = std::vector<std::pair<int, int>>;

Eigen::Vector3d to_frame(const Eigen::Vector3d& x, int axis) {
  return {x[frame_axis(axis, 0)], x[frame_axis(axis, 1)], x[frame_axis(axis, 2)]};
}

VesselMesh build_network(const NetworkSpec& spec, const NetworkLayout& layout) {
  namespace occ = gmsh::model::occ;
  const double length = spec.box[spec.axis];
  DimTags parts;
  for (int i = 0; i < static_cast<int>(spec.segments.size()); ++i) {
    const NetworkSegment& s = spec.segments[i];
    const double r = 0.5 * s.diameter;
    Eigen::Vector3d a = to_frame(s.from, spec.axis), b = to_frame(s.to, spec.axis);
    const Eigen::Vector3d dir = (b - a).normalized();
    // An end on a box face goes on past it far enough for the flat cut to miss its cap (the
    // layout keeps such ends within 60 degrees of the axis: |dir_z| >= 1/2).
    const double past = r * (std::sqrt(1 - dir[2] * dir[2]) / std::abs(dir[2]) + 1);
    if (layout.nodes[layout.ends[i][0]].on_face) a -= past * dir;
    if (layout.nodes[layout.ends[i][1]].on_face) b += past * dir;
    const Eigen::Vector3d d = b - a;
    parts.emplace_back(3, occ::addCylinder(a[0], a[1], a[2], d[0], d[1], d[2], r));
  }
  for (const NetworkNode& node : layout.nodes) {
    if (node.sphere_radius == 0) continue;
    const Eigen::Vector3d x = to_frame(node.point, spec.axis);
    parts.emplace_back(3, occ::addSphere(x[0], x[1], x[2], node.sphere_radius));
  }
  DimTags lumen{parts[0]};
  std::vector<DimTags> map;
  if (parts.size() > 1) {
    DimTags fused;
    occ::fuse({parts[0]}, DimTags(parts.begin() + 1, parts.end()), fused, map);
    lumen = fused;
  }
  const Eigen::Vector3d frame_box = to_frame(spec.box, spec.axis);
  DimTags cut;
  occ::intersect(lumen, {{3, occ::addBox(0, 0, 0, frame_box[0], frame_box[1], length)}}, cut, map);
  if (cut.size() != 1 || cut[0].first != 3)
    throw std::runtime_error("gmsh: the network's segments did not fuse into one lumen (" +
                             std::to_string(cut.size()) + " pieces)");
  occ::synchronize();
  if (spec.fillet_radius > 0) cut = {round_creases(cut[0], spec.fillet_radius, length, "the network")};
  DimTags faces;
  gmsh::model::getBoundary(cut, faces, false, false, false);
  keep_only_surfaces(without_end_caps(faces, length));
  return mesh_periodic_wall(spec.axis, spec.box, spec.element_size, 0.0, spec.fillet_radius > 0);
}

}  // namespace

VesselMesh network(const NetworkSpec& spec) {
  const NetworkLayout layout = network_layout(spec);
  return with_gmsh("the network", [&] { return build_network(spec, layout); });
}

}  // namespace rbcflow
