#include "geometry/vessel/vessel_branches.h"

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

}  // namespace

std::vector<VesselBranch> tube_branches(const TubeSpec& spec) { return {axis_branch(spec, 0.0)}; }

std::vector<VesselBranch> constriction_branches(const ConstrictionSpec& spec) {
  return {axis_branch(spec.tube, spec.centre)};
}

std::vector<VesselBranch> bifurcation_branches(const BifurcationSpec& spec) {
  const BifurcationLayout l = bifurcation_layout(spec);
  const TubeSpec& t = spec.tube;
  const Eigen::Vector2d c = frame_centre(t);
  const double half = 0.5 * t.box[t.axis], split = spec.centre;
  std::vector<VesselBranch> b{{box_point(t.axis, c[0], c[1], split - half), box_point(t.axis, c[0], c[1], split),
                               0.5 * t.diameter}};
  for (int i = 0; i < 2; ++i) {
    const double x = c[0] + (i == 0 ? 1 : -1) * l.offset;
    b.push_back({box_point(t.axis, x, c[1], split), box_point(t.axis, x, c[1], split + half),
                 0.5 * spec.daughter_diameters[i]});
  }
  return b;
}

std::vector<VesselBranch> network_branches(const NetworkSpec& spec) {
  std::vector<VesselBranch> b;
  for (const NetworkSegment& s : spec.segments) b.push_back({s.from, s.to, 0.5 * s.diameter});
  return b;
}

}  // namespace rbcflow
