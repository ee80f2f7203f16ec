// The periodic bifurcation of vessel.h: parent half, split, two-daughter loop, merge. Built in
// the frame of vessel_periodic.h with the split at L/4 and the merge at 3L/4 (so the parent
// crosses the box face, where it is cut into two periodic end circles), then shifted along the
// axis to put the split at `centre`.
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vessel/crease_fillet.h"
#include "geometry/vessel/vessel.h"
#include "geometry/vessel/vessel_periodic.h"
#include "geometry/format_number.h"

namespace rbcflow {

namespace {

using DimTags = std::vector<std::pair<int, int>>;

// A solid capsule end of the parent: the cylinder of radius R from z = z_face to z = z_joint,
// closed by a hemisphere centred at z_joint (a revolved profile: no tangent boolean).
int parent_half(const Eigen::Vector2d& c, double radius, double z_face, double z_joint) {
  namespace occ = gmsh::model::occ;
  const double tip = z_joint + (z_joint > z_face ? radius : -radius);
  const int a0 = occ::addPoint(c[0], c[1], z_face), a1 = occ::addPoint(c[0] + radius, c[1], z_face);
  const int a2 = occ::addPoint(c[0] + radius, c[1], z_joint), centre = occ::addPoint(c[0], c[1], z_joint);
  const int a3 = occ::addPoint(c[0], c[1], tip);
  const int loop = occ::addCurveLoop({occ::addLine(a0, a1), occ::addLine(a1, a2), occ::addCircleArc(a2, centre, a3),
                                      occ::addLine(a3, a0)});
  const int profile = occ::addPlaneSurface({loop});
  DimTags out;
  occ::revolve({{2, profile}}, c[0], c[1], 0, 0, 0, 1, 2 * std::numbers::pi, out);
  for (const auto& [dim, tag] : out)
    if (dim == 3) return tag;
  throw std::runtime_error("gmsh: revolving the parent profile gave no volume");
}

// Daughter i (side = +1 or -1 along the frame's x) as a pipe of a disk along its centreline.
int daughter(const Eigen::Vector2d& c, double z_split, double z_merge, double alpha, double radius, int side,
             double offset, double straight, double bend, double parallel) {
  namespace occ = gmsh::model::occ;
  const double s = side, sa = std::sin(alpha), ca = std::cos(alpha);
  // Frame points in the plane y = c[1]; mirror(z) reflects about the middle of the loop.
  auto point = [&](double x, double z) { return occ::addPoint(c[0] + s * x, c[1], z); };
  auto mirror = [&](double z) { return z_merge - (z - z_split); };
  const double x1 = straight * sa, z1 = z_split + straight * ca;  // end of the straight part
  const double xc = x1 - bend * ca, zc = z1 + bend * sa;          // centre of the bend
  const double z2 = zc;                                           // start of the parallel part
  std::vector<int> curves;
  const int p0 = point(0, z_split), p1 = straight > 0 ? point(x1, z1) : p0;
  if (straight > 0) curves.push_back(occ::addLine(p0, p1));
  const int c1 = point(xc, zc), p2 = point(offset, z2);
  curves.push_back(occ::addCircleArc(p1, c1, p2));
  const int p3 = parallel > 0 ? point(offset, mirror(z2)) : p2;
  if (parallel > 0) curves.push_back(occ::addLine(p2, p3));
  const int c2 = point(xc, mirror(zc)), p4 = straight > 0 ? point(x1, mirror(z1)) : point(0, z_merge);
  curves.push_back(occ::addCircleArc(p3, c2, p4));
  if (straight > 0) curves.push_back(occ::addLine(p4, point(0, z_merge)));
  const int wire = occ::addWire(curves);
  // The disk starts perpendicular to the first direction (s sin a, 0, cos a).
  const int disk = occ::addDisk(0, 0, 0, radius, radius);
  occ::rotate({{2, disk}}, 0, 0, 0, 0, 1, 0, s * alpha);
  occ::translate({{2, disk}}, c[0], c[1], z_split);
  DimTags out;
  occ::addPipe({{2, disk}}, wire, out);
  occ::remove({{2, disk}}, true);
  for (const auto& [dim, tag] : out)
    if (dim == 3) return tag;
  throw std::runtime_error("gmsh: the daughter pipe gave no volume");
}

VesselMesh build_bifurcation(const BifurcationSpec& spec, const BifurcationLayout& layout) {
  namespace occ = gmsh::model::occ;
  const TubeSpec& t = spec.tube;
  const double length = t.box[t.axis], radius = 0.5 * t.diameter;
  const double z_split = 0.25 * length, z_merge = 0.75 * length;
  const double alpha = 0.5 * spec.angle_deg * std::numbers::pi / 180.0;
  const Eigen::Vector2d c = frame_centre(t);
  const int lower = parent_half(c, radius, 0.0, z_split);
  const int upper = parent_half(c, radius, length, z_merge);
  DimTags tools{{3, upper}};
  for (int i = 0; i < 2; ++i)
    tools.emplace_back(3, daughter(c, z_split, z_merge, alpha, 0.5 * spec.daughter_diameters[i], i == 0 ? 1 : -1,
                                   layout.offset, layout.straight[i], layout.bend_radius[i], layout.parallel[i]));
  DimTags fused;
  std::vector<DimTags> map;
  occ::fuse({{3, lower}}, tools, fused, map);
  if (fused.size() != 1 || fused[0].first != 3)
    throw std::runtime_error("gmsh: the parent and daughters did not fuse into one volume");
  occ::synchronize();
  if (spec.fillet_radius > 0) fused = {round_creases(fused[0], spec.fillet_radius, length, "the bifurcation")};
  DimTags faces;
  gmsh::model::getBoundary(fused, faces, false, false, false);
  keep_only_surfaces(without_end_caps(faces, length));
  return mesh_periodic_wall(t.axis, t.box, t.element_size, spec.centre - z_split, spec.fillet_radius > 0);
}

}  // namespace

BifurcationLayout bifurcation_layout(const BifurcationSpec& spec) {
  const TubeSpec& t = spec.tube;
  validate_tube(t);
  const double length = t.box[t.axis], radius = 0.5 * t.diameter;
  const double r0 = 0.5 * spec.daughter_diameters[0], r1 = 0.5 * spec.daughter_diameters[1];
  for (double d : spec.daughter_diameters)
    if (!(d > 0 && d < t.diameter))
      throw std::invalid_argument("bifurcation daughter diameter " + format_number(d) + " must be in (0, " +
                                  format_number(t.diameter) + "), below the parent's");
  if (!(spec.angle_deg > 0 && spec.angle_deg < 180))
    throw std::invalid_argument("bifurcation angle " + format_number(spec.angle_deg) + " must be in (0, 180) degrees");
  if (!(spec.centre >= 0 && spec.centre <= length))
    throw std::invalid_argument("bifurcation centre " + format_number(spec.centre) + " must be in [0, " + format_number(length) +
                                "], the box side along the axis");
  if (!(spec.fillet_radius >= 0 && spec.fillet_radius < std::min(r0, r1)))
    throw std::invalid_argument("bifurcation fillet radius " + format_number(spec.fillet_radius) + " must be in [0, " +
                                format_number(std::min(r0, r1)) + "), below the smaller daughter's radius");
  if (!(t.element_size < std::min(r0, r1)))
    throw std::invalid_argument("bifurcation element size " + format_number(t.element_size) +
                                " must be below the daughter radius " + format_number(std::min(r0, r1)));
  if (4 * radius >= length)
    throw std::invalid_argument("bifurcation box side along the axis " + format_number(length) +
                                " must exceed twice the parent diameter, " + format_number(2 * t.diameter));
  BifurcationLayout l;
  l.offset = std::max(r0, r1) + 0.25 * (r0 + r1);
  const double lateral = 0.5 * t.box[frame_axis(t.axis, 0)];
  if (l.offset + std::max(r0, r1) >= lateral)
    throw std::invalid_argument("bifurcation daughters reach " + format_number(l.offset + std::max(r0, r1)) +
                                " from the axis; the box gives " + format_number(lateral) + " (half its side " +
                                std::string(1, "xyz"[frame_axis(t.axis, 0)]) + ")");
  const double alpha = 0.5 * spec.angle_deg * std::numbers::pi / 180.0;
  for (int i = 0; i < 2; ++i) {
    const double r = i == 0 ? r0 : r1;
    // Bend radius 2 r unless the bend alone must reach the offset (a steep angle).
    double bend = 2 * r, straight = 0;
    if (bend * (1 - std::cos(alpha)) >= l.offset) {
      bend = l.offset / (1 - std::cos(alpha));
    } else {
      straight = (l.offset - bend * (1 - std::cos(alpha))) / std::sin(alpha);
    }
    const double transition = straight * std::cos(alpha) + bend * std::sin(alpha);
    const double parallel = 0.5 * length - 2 * transition;
    if (parallel < 0)
      throw std::invalid_argument("bifurcation daughters at " + format_number(spec.angle_deg) + " degrees need " +
                                  format_number(2 * transition) + " from split to merge, half the box side along the axis (" +
                                  format_number(0.5 * length) + "): make that side at least " + format_number(4 * transition) +
                                  " or widen the angle");
    l.straight[i] = straight;
    l.bend_radius[i] = bend;
    l.parallel[i] = parallel < 1e-9 * length ? 0.0 : parallel;
  }
  return l;
}

VesselMesh bifurcation(const BifurcationSpec& spec) {
  const BifurcationLayout layout = bifurcation_layout(spec);
  return with_gmsh("the bifurcation", [&] { return build_bifurcation(spec, layout); });
}

}  // namespace rbcflow
