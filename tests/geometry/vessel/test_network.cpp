#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "geometry/vessel/mesh_check.h"
#include "geometry/vessel/mesh_orientation.h"
#include "geometry/vessel/network.h"
#include "tests/geometry/vessel/fillet_folds.h"

using namespace rbcflow;

namespace {

NetworkSegment segment(Eigen::Vector3d from, Eigen::Vector3d to, double diameter) { return {from, to, diameter}; }

// The two-junction network of the case format: a parent (D = 3) splits at z = 4 into daughters
// (2.4, 2.2) that meet again at z = 12, in a 12 x 6 x 16 box.
NetworkSpec loop_network(double h = 0.3) {
  NetworkSpec s;
  s.axis = 2;
  s.box = Eigen::Vector3d(12, 6, 16);
  s.element_size = h;
  s.segments = {segment({6, 3, 0}, {6, 3, 4}, 3.0),    segment({6, 3, 4}, {3.5, 3, 8}, 2.4),
                segment({6, 3, 4}, {8.5, 3, 8}, 2.2),  segment({3.5, 3, 8}, {6, 3, 12}, 2.4),
                segment({8.5, 3, 8}, {6, 3, 12}, 2.2), segment({6, 3, 12}, {6, 3, 16}, 3.0)};
  return s;
}

// One straight segment across the box along x: the tube of D = 2 in a 6 x 4 x 4 box.
NetworkSpec straight(double h) {
  NetworkSpec s;
  s.axis = 0;
  s.box = Eigen::Vector3d(6, 4, 4);
  s.element_size = h;
  s.segments = {segment({0, 2, 2}, {6, 2, 2}, 2.0)};
  return s;
}

// The distance from x to the centreline segment [a, b], and where along it (0..1).
std::pair<double, double> from_centreline(const Eigen::Vector3d& x, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double t = (x - a).dot(b - a) / (b - a).squaredNorm();
  return {(x - a - t * (b - a)).norm(), t};
}

// How far x is from the nearest surface the lumen is made of: a segment's cylinder (within its
// length, or past an end on a box face, where the cylinder goes on to the cut) or a junction
// sphere.
double off_primitives(const Eigen::Vector3d& x, const NetworkSpec& s, const NetworkLayout& l) {
  const double length = s.box[s.axis];
  auto on_face = [&](const Eigen::Vector3d& p) { return p[s.axis] == 0 || p[s.axis] == length; };
  double best = 1e300;
  for (const NetworkSegment& g : s.segments) {
    const auto [d, t] = from_centreline(x, g.from, g.to);
    if ((t >= -1e-9 || on_face(g.from)) && (t <= 1 + 1e-9 || on_face(g.to)))
      best = std::min(best, std::abs(d - 0.5 * g.diameter));
  }
  for (const NetworkNode& n : l.nodes)
    if (n.sphere_radius > 0) best = std::min(best, std::abs((x - n.point).norm() - n.sphere_radius));
  return best;
}

void expect_invalid(const NetworkSpec& s, const std::string& words) {
  try {
    network_layout(s);
    FAIL() << "no error, expected one about " << words;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
  }
}

}  // namespace

// The junctions are found: the parent's two ends are one node on the face, the split and the
// merge join three segments each, the daughters' middles two.
TEST(Network, LayoutFindsJunctionsAndThePeriodicSeam) {
  const NetworkLayout l = network_layout(loop_network());
  ASSERT_EQ(l.nodes.size(), 5u);
  int on_face = 0, three = 0;
  for (const NetworkNode& n : l.nodes) {
    on_face += n.on_face;
    three += n.segments.size() == 3;
  }
  EXPECT_EQ(on_face, 1);
  EXPECT_EQ(three, 2);
  EXPECT_EQ(l.ends[0][0], l.ends[5][1]);  // z = 0 and z = 16: one node
}

// A closed, oriented wall (check_mesh passed in the builder) whose every node lies on a
// segment's cylinder or a junction sphere: the CAD surfaces, to OCC's tolerance 1e-7.
TEST(Network, WallLiesOnTheCylindersAndSpheres) {
  const NetworkSpec s = loop_network();
  const VesselMesh wall = network(s);
  const MeshQuality q = check_mesh(wall);
  std::printf("network h = %.2f: %d nodes, %d triangles, min angle %.1f deg, lumen volume %.3f\n", s.element_size,
              wall.surface.num_points(), wall.surface.num_triangles(), q.min_angle_deg, -0.5 * lumen_flux(wall));
  EXPECT_EQ(wall.period, Eigen::Vector3d(0, 0, 16));
  EXPECT_LT(lumen_flux(wall), 0.0);
  EXPECT_GT(q.min_angle_deg, 10.0);
  const NetworkLayout l = network_layout(s);
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    ASSERT_LT(off_primitives(x, s, l), 1e-6) << x.transpose();
  }
}

// fillet_radius rounds the creases where the daughters meet the junction spheres: sharp, two
// neighbouring triangles there fold by ~40-50 degrees; rounded with r = 0.5, the steepest fold is
// the fillet's own curvature resolved by edges of ~h, h / r = 0.6 rad (34 degrees), up to 45 for
// edges of 1.3 h. Nodes away from the creases stay on the segments' cylinders: a crease runs
// within the junction sphere, or, between two segments leaving a junction at an angle theta,
// to where they part, (r_i + r_j) / (2 sin(theta / 2)) along them; the fillet reaches r beyond.
TEST(Network, FilletRoundsTheJunctionCreases) {
  NetworkSpec s = loop_network();
  s.fillet_radius = 0.5;
  const FilletFolds f = sharp_and_rounded(loop_network(), s.fillet_radius, [](const NetworkSpec& n) { return network(n); });
  const VesselMesh& rounded = f.rounded;
  EXPECT_LT(f.quality.max_fold_deg, 45.0);
  EXPECT_LT(f.quality.max_fold_deg, f.sharp_fold_deg - 5.0);
  EXPECT_LT(lumen_flux(rounded), 0.0);
  const NetworkLayout l = network_layout(s);
  std::vector<double> crease_reach(l.nodes.size(), 0.0);
  for (std::size_t n = 0; n < l.nodes.size(); ++n) {
    const NetworkNode& node = l.nodes[n];
    if (node.sphere_radius == 0) continue;
    double reach = node.sphere_radius;
    for (int i : node.segments)
      for (int j : node.segments) {
        if (i >= j) continue;
        auto outward = [&](int k) {
          const NetworkSegment& g = s.segments[k];
          return Eigen::Vector3d(((g.from - node.point).norm() < 1e-9 ? g.to - g.from : g.from - g.to).normalized());
        };
        const double theta = std::acos(std::clamp(outward(i).dot(outward(j)), -1.0, 1.0));
        reach = std::max(reach, 0.5 * (s.segments[i].diameter + s.segments[j].diameter) / (2 * std::sin(0.5 * theta)));
      }
    crease_reach[n] = reach + s.fillet_radius + s.element_size;
  }
  int away = 0;
  for (int i = 0; i < rounded.surface.num_points(); ++i) {
    const Eigen::Vector3d x = rounded.surface.points.row(i);
    bool near_crease = false;
    for (std::size_t n = 0; n < l.nodes.size(); ++n)
      near_crease |= crease_reach[n] > 0 && (x - l.nodes[n].point).norm() < crease_reach[n];
    if (near_crease) continue;
    EXPECT_LT(off_primitives(x, s, l), 1e-6) << x.transpose();
    ++away;
  }
  std::printf("%d of %d nodes away from the creases\n", away, rounded.surface.num_points());
  EXPECT_GT(away, 300);
}

// The single segment is the tube: its enclosed volume converges to pi r^2 L at second order in
// the element size (the chordal error of the inscribed polygon, (h / r)^2 / 6 of the area).
TEST(Network, StraightSegmentVolumeConvergesAtSecondOrder) {
  const double exact = std::numbers::pi * 1.0 * 6.0;
  double previous = 0;
  for (double h : {0.4, 0.2, 0.1}) {
    const VesselMesh wall = network(straight(h));
    EXPECT_EQ(wall.period, Eigen::Vector3d(6, 0, 0));
    const double error = std::abs(-0.5 * lumen_flux(wall) / exact - 1);
    std::printf("straight segment h = %.2f: volume error %.3e\n", h, error);
    EXPECT_LT(error, h * h / 6 * 1.5);
    if (previous > 0) {
      EXPECT_GT(previous / error, 3.0);  // order > 1.58
    }
    previous = error;
  }
}

// A zig-zag vessel crossing the box face at 30 degrees to the axis: the two cut ellipses
// match, so the periodic seam is merged (mesh_periodic_wall throws otherwise).
TEST(Network, ObliqueCrossingOfTheBoxFaceIsPeriodic) {
  NetworkSpec s;
  s.axis = 2;
  s.box = Eigen::Vector3d(10, 5, 8);
  s.element_size = 0.3;
  const double run = 2 * std::tan(std::numbers::pi / 6);  // over 2 along z
  s.segments = {segment({5 - run, 2.5, 0}, {5 + run, 2.5, 4}, 2.0)};
  expect_invalid(s, "does not meet its periodic partner: no segment ends at [3.845, 2.5, 8]");
  s.segments = {segment({5 - run, 2.5, 0}, {5 + run, 2.5, 4}, 2.0), segment({5 + run, 2.5, 4}, {5 - run, 2.5, 8}, 2.0)};
  expect_invalid(s, "meet through the box face at [3.845, 2.5, 0] with another direction");
  s.segments = {segment({5, 2.5, 0}, {5 + run, 2.5, 2}, 2.0), segment({5 + run, 2.5, 2}, {5 - run, 2.5, 6}, 2.0),
                segment({5 - run, 2.5, 6}, {5, 2.5, 8}, 2.0)};
  const VesselMesh wall = network(s);
  EXPECT_EQ(wall.period, Eigen::Vector3d(0, 0, 8));
  const NetworkLayout l = network_layout(s);
  for (int i = 0; i < wall.surface.num_points(); ++i) {
    const Eigen::Vector3d x = wall.surface.points.row(i);
    ASSERT_LT(off_primitives(x, s, l), 1e-6) << x.transpose();
  }
  s.box[0] = 7.0;  // the bend at x = 6.155 has its wall at 7.155
  expect_invalid(s, "segment 0 leaves the box sideways");
}

// Every bad description is refused naming the segment and what is wrong.
TEST(Network, BadLayoutsNameTheSegment) {
  NetworkSpec s = loop_network();
  s.fillet_radius = 1.1;
  expect_invalid(s, "segment 2: fillet radius 1.1 must be below its radius 1.1");
  s = loop_network();
  s.segments[4].to = {8.5, 3, 12};  // the 2.2 daughter ends beside the merge
  expect_invalid(s, "segment 4: end [8.5, 3, 12] is open");

  s = loop_network();
  s.segments[5].diameter = 2.8;
  expect_invalid(s, "segment 0 and segment 5 meet through the box face");

  s = loop_network();
  s.segments[1].to = s.segments[3].from = {1.0, 3, 8};  // the 2.4 daughter at x = 1 +- 1.2
  expect_invalid(s, "segment 1 leaves the box sideways");

  s = loop_network();
  s.segments.push_back(segment({6, 3, 4}, {6, 3, 12}, 2.0));  // straight through the loop
  s.segments[6].to = {6, 3, 11};
  expect_invalid(s, "segment 6: end [6, 3, 11] is open");
  s.segments[6].to = {6, 3, 12};
  // A third path between the junctions, 2.5 from the daughters' bends: clear of them.
  EXPECT_NO_THROW(network_layout(s));
  s.segments[6].to = {7.6, 3, 8};  // ending inside the 2.2 daughter
  s.segments.push_back(segment({7.6, 3, 8}, {6, 3, 12}, 2.0));
  expect_invalid(s, "segment 2 and segment 6 overlap: from their junction at [6, 3, 4], segment 6 runs inside segment 2");

  s = loop_network();  // the same segment twice, beside the parent
  s.segments.push_back(segment({1.2, 3, 2}, {1.2, 3, 6}, 1.0));
  s.segments.push_back(segment({1.2, 3, 6}, {1.2, 3, 2}, 1.0));
  expect_invalid(s, "segment 6 and segment 7 overlap");

  s = straight(0.2);
  s.segments.push_back(segment({1, 2, 0.2}, {5, 2, 0.2}, 0.5));
  expect_invalid(s, "segment 1 leaves the box sideways");

  s = straight(0.2);
  s.segments = {segment({0, 2, 2}, {3, 2, 2}, 2.0), segment({3, 2, 2}, {6, 2, 2}, 2.0),
                segment({1, 2, 2}, {1.1, 2, 2}, 0.5)};
  expect_invalid(s, "segment 2: end [1, 2, 2] is open");

  s = straight(0.2);
  s.segments[0].diameter = 0.3;
  expect_invalid(s, "segment 0: diameter 0.3 must exceed twice the element size 0.2");

  s = straight(0.2);  // a straight run through a node near the face needs no sphere
  s.segments = {segment({0, 2, 2}, {0.8, 2, 2}, 2.0), segment({0.8, 2, 2}, {6, 2, 2}, 2.0)};
  EXPECT_NO_THROW(network_layout(s));

  s = loop_network();  // the split 1 from the box face: its sphere (radius 1.5) crosses it
  s.segments[0].to = s.segments[1].from = s.segments[2].from = {6, 3, 1};
  expect_invalid(s, "junction at [6, 3, 1] (segment 0) is within its radius 1.5 of a box face");
}

// Two vessels side by side, each periodic, never joined: refused as two pieces.
TEST(Network, DisconnectedPiecesAreRefused) {
  NetworkSpec s;
  s.axis = 2;
  s.box = Eigen::Vector3d(10, 5, 6);
  s.element_size = 0.3;
  s.segments = {segment({2.5, 2.5, 0}, {2.5, 2.5, 6}, 2.0), segment({7.5, 2.5, 0}, {7.5, 2.5, 6}, 2.0)};
  expect_invalid(s, "segment 1 is not connected to segment 0");
}
