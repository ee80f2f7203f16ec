// network_layout: the checks of a network description and its junctions, without gmsh.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "geometry/vessel/network.h"
#include "geometry/format_number.h"

namespace rbcflow {
namespace {

std::string point_text(const Eigen::Vector3d& x) {
  std::string text = "[";
  for (int k = 0; k < 3; ++k) text.append(format_number(x[k])).append(k < 2 ? ", " : "]");
  return text;
}

std::string segment_name(int i) { return "segment " + std::to_string(i); }

[[noreturn]] void invalid(const std::string& what) { throw std::invalid_argument("network " + what); }

// The distance between the segments [p0, p1] and [q0, q1] (the closest points by the clamped
// minimisation of |p(s) - q(t)|^2 over s, t in [0, 1]).
double segment_distance(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                        const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r), c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  double s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  return (p0 + s * d1 - (q0 + t * d2)).norm();
}

struct Checker {
  const NetworkSpec& spec;
  double length = 0, tolerance = 0;
  NetworkLayout layout;

  double radius(int i) const { return 0.5 * spec.segments[i].diameter; }
  const Eigen::Vector3d& end(int i, int side) const {
    return side == 0 ? spec.segments[i].from : spec.segments[i].to;
  }
  // The unit direction of segment i out of its end `side`.
  Eigen::Vector3d outward(int i, int side) const {
    return (side == 0 ? end(i, 1) - end(i, 0) : end(i, 0) - end(i, 1)).normalized();
  }

  void check_segment(int i) const {
    const NetworkSegment& s = spec.segments[i];
    const double r = radius(i);
    if (!(s.diameter > 2 * spec.element_size))
      invalid(segment_name(i) + ": diameter " + format_number(s.diameter) + " must exceed twice the element size " +
              format_number(spec.element_size));
    if (!(spec.fillet_radius < r))
      invalid(segment_name(i) + ": fillet radius " + format_number(spec.fillet_radius) + " must be below its radius " +
              format_number(r));
    if ((s.to - s.from).norm() <= tolerance) invalid(segment_name(i) + ": from and to are the same point");
    for (int side = 0; side < 2; ++side) {
      const Eigen::Vector3d& x = end(i, side);
      if (x[spec.axis] < -tolerance || x[spec.axis] > length + tolerance)
        invalid(segment_name(i) + ": end " + point_text(x) + " is outside the box along " +
                std::string(1, "xyz"[spec.axis]) + " (0 to " + format_number(length) + ")");
      for (int d = 0; d < 3; ++d)
        if (d != spec.axis && !(x[d] - r > 0 && x[d] + r < spec.box[d]))
          invalid(segment_name(i) + " leaves the box sideways: its wall at " + point_text(x) + " reaches " +
                  std::string(1, "xyz"[d]) + " = " + format_number(x[d] - r) + " .. " + format_number(x[d] + r) +
                  "; the box gives 0 .. " + format_number(spec.box[d]));
    }
  }

  // The node of end `side` of segment i, added where no node is yet.
  int node_of(int i, int side) {
    Eigen::Vector3d x = end(i, side);
    const bool face = std::abs(x[spec.axis]) <= tolerance || std::abs(x[spec.axis] - length) <= tolerance;
    if (face) x[spec.axis] = 0.0;
    for (int n = 0; n < static_cast<int>(layout.nodes.size()); ++n)
      if ((layout.nodes[n].point - x).norm() <= tolerance) {
        layout.nodes[n].segments.push_back(i);
        return n;
      }
    layout.nodes.push_back({x, {i}, face});
    return static_cast<int>(layout.nodes.size()) - 1;
  }

  // The end of segment i at node n (the first, for a segment with both ends there).
  int side_at(int i, int n) const { return layout.ends[i][0] == n ? 0 : 1; }

  void check_node(int n) const {
    const NetworkNode& node = layout.nodes[n];
    const int first = node.segments[0];
    if (node.segments.size() == 1) {
      const Eigen::Vector3d& x = end(first, side_at(first, n));
      if (!node.on_face)
        invalid(segment_name(first) + ": end " + point_text(x) + " is open: it meets no other segment and is not " +
                "on a box face along " + std::string(1, "xyz"[spec.axis]));
      Eigen::Vector3d partner = x;
      partner[spec.axis] = x[spec.axis] > 0.5 * length ? 0.0 : length;
      invalid(segment_name(first) + ": the open end " + point_text(x) + " does not meet its periodic partner: " +
              "no segment ends at " + point_text(partner));
    }
    if (!node.on_face) {
      const double a = node.point[spec.axis], r = node.sphere_radius;
      if (a - r < 0 || a + r > length)
        invalid("junction at " + point_text(node.point) + " (" + segment_name(first) + ") is within its radius " +
                format_number(r) + " of a box face along " + std::string(1, "xyz"[spec.axis]) +
                ": move it inside, or end the segments on the face");
      return;
    }
    if (node.segments.size() != 2)
      invalid("junction at " + point_text(node.point) + " (" + segment_name(first) +
              ") is on a box face along the axis: only a single vessel may cross the box face");
    // A segment across the whole box along the axis is its own partner.
    const int second = node.segments[1];
    const Eigen::Vector3d a = outward(first, side_at(first, n));
    const Eigen::Vector3d b = outward(second, second == first ? 1 : side_at(second, n));
    if (std::abs(radius(first) - radius(second)) > tolerance || (a + b).norm() > 1e-6)
      invalid(segment_name(first) + " and " + segment_name(second) + " meet through the box face at " +
              point_text(node.point) + " with another " +
              (std::abs(radius(first) - radius(second)) > tolerance ? "diameter" : "direction") +
              ": periodic partners must continue each other");
    if (std::abs(a[spec.axis]) < 0.5)
      invalid(segment_name(first) + " crosses the box face at " + point_text(node.point) +
              " more than 60 degrees from the axis: let the vessel cross the face closer to the axis");
  }

  double sphere_radius(int n) const {
    const NetworkNode& node = layout.nodes[n];
    if (node.on_face) return 0.0;
    const int a = node.segments[0], b = node.segments.size() == 2 ? node.segments[1] : -1;
    if (b >= 0 && radius(a) == radius(b) && outward(a, side_at(a, n)).dot(outward(b, side_at(b, n))) < -1 + 1e-12)
      return 0.0;
    double widest = 0;
    for (int i : node.segments) widest = std::max(widest, radius(i));
    return widest;
  }

  // Whether the end `side` of segment j lies inside segment i's cylinder.
  bool end_inside(int j, int side, int i) const {
    const Eigen::Vector3d a = end(i, 0), d = end(i, 1) - a, x = end(j, side) - a;
    const double t = x.dot(d) / d.squaredNorm();
    return t >= 0 && t <= 1 && (x - t * d).norm() < radius(i);
  }

  // Segments i and j share node n: neither may end inside the other (a duplicate, or a segment
  // leaving the junction so close to the other that it runs inside it).
  void check_parting(int i, int j, int n) const {
    for (const auto& [inner, outer] : {std::pair{i, j}, std::pair{j, i}}) {
      const int far_side = side_at(inner, n) == 0 ? 1 : 0;
      if (end_inside(inner, far_side, outer))
        invalid(segment_name(i) + " and " + segment_name(j) + " overlap: from their junction at " +
                point_text(layout.nodes[n].point) + ", " + segment_name(inner) + " runs inside " +
                segment_name(outer));
    }
  }

  void check_pair(int i, int j) const {
    std::vector<int> shared;
    for (int a : layout.ends[i])
      for (int b : layout.ends[j])
        if (a == b && std::find(shared.begin(), shared.end(), a) == shared.end()) shared.push_back(a);
    for (int n : shared)
      if (!layout.nodes[n].on_face) check_parting(i, j, n);
    if (!shared.empty()) return;
    Eigen::Vector3d shift = Eigen::Vector3d::Zero();
    for (int k = -1; k <= 1; ++k) {
      shift[spec.axis] = k * length;
      const double d = segment_distance(end(i, 0), end(i, 1), end(j, 0) + shift, end(j, 1) + shift);
      if (d <= radius(i) + radius(j))
        invalid(segment_name(i) + " and " + segment_name(j) + " overlap: their centrelines come " + format_number(d) +
                " apart" + (k != 0 ? " (through the periodic box)" : "") + ", below the sum of their radii " +
                format_number(radius(i) + radius(j)) + "; let them share an end point to join them");
    }
  }

  void check_connected() const {
    const int n = static_cast<int>(layout.nodes.size());
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto root = [&](int a) {
      while (parent[a] != a) a = parent[a] = parent[parent[a]];
      return a;
    };
    for (const auto& e : layout.ends) parent[root(e[0])] = root(e[1]);
    for (int i = 1; i < static_cast<int>(layout.ends.size()); ++i)
      if (root(layout.ends[i][0]) != root(layout.ends[0][0]))
        invalid(segment_name(i) + " is not connected to " + segment_name(0) + ": the network must be one vessel");
  }
};

}  // namespace

NetworkLayout network_layout(const NetworkSpec& spec) {
  if (spec.axis < 0 || spec.axis > 2) invalid("axis must be 0, 1 or 2");
  if (!(spec.box.minCoeff() > 0)) invalid("box sides must be positive");
  if (!(spec.element_size > 0)) invalid("element size must be positive");
  if (!(spec.fillet_radius >= 0)) invalid("fillet radius must not be negative");
  if (spec.segments.empty()) invalid("needs at least one segment");
  Checker c{spec, spec.box[spec.axis], 1e-6 * spec.box[spec.axis], {}};
  const int count = static_cast<int>(spec.segments.size());
  for (int i = 0; i < count; ++i) c.check_segment(i);
  for (int i = 0; i < count; ++i) c.layout.ends.push_back({c.node_of(i, 0), c.node_of(i, 1)});
  for (int n = 0; n < static_cast<int>(c.layout.nodes.size()); ++n) {
    if (c.layout.nodes[n].segments.size() > 1) c.layout.nodes[n].sphere_radius = c.sphere_radius(n);
    c.check_node(n);
  }
  for (int i = 0; i < count; ++i)
    for (int j = i + 1; j < count; ++j) c.check_pair(i, j);
  c.check_connected();
  return c.layout;
}

}  // namespace rbcflow
