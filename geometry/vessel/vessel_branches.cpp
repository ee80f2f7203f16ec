#include "geometry/vessel/vessel_branches.h"

#include <algorithm>
#include <cmath>

#include "geometry/vessel/vessel_periodic.h"

namespace rbcflow {
namespace {

// The box point of frame coordinates (x, y, s) (vessel_periodic.h).
Eigen::Vector3d box_point(int axis, double x, double y, double s) {
  Eigen::Vector3d p;
  p[frame_axis(axis, 0)] = x;
  p[frame_axis(axis, 1)] = y;
  p[frame_axis(axis, 2)] = s;
  return p;
}

VesselBranch axis_branch(const TubeSpec& t, double start) {
  const Eigen::Vector2d c = frame_centre(t);
  return {box_point(t.axis, c[0], c[1], start), box_point(t.axis, c[0], c[1], start + t.box[t.axis]),
          0.5 * t.diameter};
}

// The clear part of a branch of `length` whose ends are `margin_from` and `margin_to` from the
// nearest cross-section that is its own; the middle where they overlap.
void set_clear(VesselBranch& b, double length, double margin_from, double margin_to) {
  b.clear_from = margin_from / length;
  b.clear_to = 1 - margin_to / length;
  if (b.clear_from > b.clear_to) b.clear_from = b.clear_to = 0.5 * (b.clear_from + b.clear_to);
}

}  // namespace

std::vector<VesselBranch> tube_branches(const TubeSpec& spec) {
  VesselBranch b = axis_branch(spec, 0.0);
  set_clear(b, spec.box[spec.axis], 0.0, 0.0);
  return {b};
}

std::vector<VesselBranch> constriction_branches(const ConstrictionSpec& spec) {
  return {axis_branch(spec.tube, spec.centre)};
}

std::vector<VesselBranch> bifurcation_branches(const BifurcationSpec& spec) {
  const BifurcationLayout l = bifurcation_layout(spec);
  const TubeSpec& t = spec.tube;
  const Eigen::Vector2d c = frame_centre(t);
  const double half = 0.5 * t.box[t.axis], split = spec.centre;
  const double R = 0.5 * t.diameter;
  std::vector<VesselBranch> b{{box_point(t.axis, c[0], c[1], split - half), box_point(t.axis, c[0], c[1], split), R}};
  set_clear(b[0], half, 2 * R, 2 * R);  // clear of the junction spheres (radius R) and the daughters
  for (int i = 0; i < 2; ++i) {
    const double x = c[0] + (i == 0 ? 1 : -1) * l.offset;
    b.push_back({box_point(t.axis, x, c[1], split), box_point(t.axis, x, c[1], split + half),
                 0.5 * spec.daughter_diameters[i]});
    const double bends = 0.5 * (half - l.parallel[i]);  // split and merge to the parallel part
    set_clear(b.back(), half, bends, bends);
  }
  return b;
}

std::vector<VesselBranch> network_branches(const NetworkSpec& spec) {
  const NetworkLayout layout = network_layout(spec);
  std::vector<VesselBranch> b;
  for (int i = 0; i < static_cast<int>(spec.segments.size()); ++i) {
    const NetworkSegment& s = spec.segments[i];
    const double r = 0.5 * s.diameter;
    b.push_back({s.from, s.to, r});
    // A cross-section at distance d from a junction along the segment is clear of the junction
    // sphere for d >= its radius, and of another segment leaving the junction at an angle theta
    // below 90 degrees to this one for d sin(theta) >= the sum of the radii (segments leaving at
    // 90 degrees or more go the other way).
    auto margin = [&](int node) {
      const NetworkNode& n = layout.nodes[node];
      if (n.on_face) return 0.0;
      const Eigen::Vector3d out = (node == layout.ends[i][0] ? s.to - s.from : s.from - s.to).normalized();
      double d = n.sphere_radius;
      for (int j : n.segments) {
        if (j == i) continue;
        const NetworkSegment& o = spec.segments[j];
        const Eigen::Vector3d other = (node == layout.ends[j][0] ? o.to - o.from : o.from - o.to).normalized();
        const double c = out.dot(other);
        if (c > 0) d = std::max(d, (r + 0.5 * o.diameter) / std::sqrt(std::max(1e-12, 1 - c * c)));
      }
      return d;
    };
    set_clear(b.back(), (s.to - s.from).norm(), margin(layout.ends[i][0]), margin(layout.ends[i][1]));
  }
  return b;
}

}  // namespace rbcflow
