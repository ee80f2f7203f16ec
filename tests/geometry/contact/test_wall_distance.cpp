#include "geometry/contact/wall_distance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "geometry/vessel/network.h"
#include "geometry/vessel/vessel.h"

using namespace rbcflow;

// A D = 3.5 tube along z in a 4 x 4 x 8 box, element size 0.2: the polygonal cross-section
// loses ~(2 pi R) h^2/(12 R) of area per unit length (chord segments), 0.4% of pi R^2.
TEST(WallDistance, TubeLumenAndSignedDistances) {
  const VesselMesh wall = tube(TubeSpec{3.5, 2, Eigen::Vector3d(4, 4, 8), 0.2});
  const double exact = std::numbers::pi * 1.75 * 1.75 * 8;
  EXPECT_NEAR(lumen_volume(wall) / exact, 1.0, 5e-3);
  const WallDistance d(wall);
  // On the axis: R, less the chord sag h^2 / (8 R) < 3e-3.
  for (double z : {-7.9, 0.0, 3.3, 8.0, 15.2}) {
    const WallDistance::Query q = d.closest({2, 2, z});
    EXPECT_NEAR(q.signed_distance, 1.75, 3e-3) << z;
    EXPECT_NEAR(q.point.z(), z, 0.2) << z;  // the image next to the query
  }
  // Beyond the wall: negative; the normal points back into the lumen.
  const WallDistance::Query out = d.closest({2 + 2.0, 2, 7.95});
  EXPECT_NEAR(out.signed_distance, -0.25, 3e-3);
  EXPECT_LT(out.normal.x(), -0.99);
}

// The smallest distance of point sets from the wall, pruned (sets far from the wall, points
// within the free ball of the last one queried), against every point queried: the same value.
// Spheres of radius 0.5 at offsets r from the axis of the D = 3.5 tube: the closest one, at
// r = 1.1, comes within 1.75 - 1.1 - 0.5 = 0.15 of the wall (less the grids' chord errors, < 0.01).
TEST(WallDistance, SmallestDistanceOfCellsEqualsEveryPointQueried) {
  const VesselMesh wall = tube(TubeSpec{3.5, 2, Eigen::Vector3d(4, 4, 8), 0.2});
  const WallDistance d(wall);
  std::vector<Eigen::MatrixX3d> cells;
  const int n = 24;
  for (const auto& [r, z] : {std::pair{0.3, 1.0}, std::pair{1.1, 4.0}, std::pair{0.8, 11.0}}) {
    Eigen::MatrixX3d points(n * n, 3);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double theta = std::numbers::pi * (i + 0.5) / n, phi = 2 * std::numbers::pi * j / n;
        points.row(i * n + j) = Eigen::RowVector3d(2 + r + 0.5 * std::sin(theta) * std::cos(phi),
                                                   2 + 0.5 * std::sin(theta) * std::sin(phi), z + 0.5 * std::cos(theta));
      }
    cells.push_back(points);
  }
  double every = std::numeric_limits<double>::infinity();
  for (const Eigen::MatrixX3d& c : cells)
    for (Eigen::Index p = 0; p < c.rows(); ++p) every = std::min(every, d.closest(c.row(p).transpose()).signed_distance);
  EXPECT_EQ(smallest_wall_distance(d, cells), every);
  EXPECT_NEAR(every, 0.15, 0.01);
  EXPECT_EQ(smallest_wall_distance(d, {}), std::numeric_limits<double>::infinity());
}

// The side of points beside ridges that jut into the lumen: the dividers of a two-junction
// network (geometry/vessel/network.h), where a triangle's own normal put a point 0.47 inside
// the lumen 0.47 beyond the wall. Points inside a segment's cylinder (by its exact radius less
// the chord sag) are in the lumen; points farther than an element from every cylinder and
// junction sphere are beyond the wall; the sign must say so for all of them, and the magnitude
// is the unsigned distance.
TEST(WallDistance, SideOfPointsBesideTheDividersOfANetwork) {
  NetworkSpec s;
  s.axis = 2;
  s.box = Eigen::Vector3d(15, 7, 20);
  s.element_size = 0.3;
  auto segment = [](Eigen::Vector3d a, Eigen::Vector3d b, double d) { return NetworkSegment{a, b, d}; };
  s.segments = {segment({7.5, 3.5, 0}, {7.5, 3.5, 4}, 4.0),     segment({7.5, 3.5, 4}, {3.7, 3.5, 10}, 3.2),
                segment({7.5, 3.5, 4}, {11.3, 3.5, 10}, 3.0),   segment({3.7, 3.5, 10}, {7.5, 3.5, 16}, 3.2),
                segment({11.3, 3.5, 10}, {7.5, 3.5, 16}, 3.0), segment({7.5, 3.5, 16}, {7.5, 3.5, 20}, 4.0)};
  const VesselMesh wall = network(s);
  const NetworkLayout layout = network_layout(s);
  const WallDistance d(wall);
  // The point of the failure: in the 3.2 daughter beside the divider at the split.
  EXPECT_GT(d.closest({7.22, 3.95, 6.38}).signed_distance, 0.3);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int inside = 0, outside = 0;
  const double sag = 0.3 * 0.3 / (8 * 1.5);
  for (int k = 0; k < 20000; ++k) {
    const Eigen::Vector3d x(15 * u(random), 7 * u(random), 20 * u(random));
    double in_cylinder = -1e300, off_everything = 1e300;  // by how much inside the nearest cylinder; clearance
    for (const NetworkSegment& g : s.segments) {
      const Eigen::Vector3d a = g.to - g.from;
      const double t = (x - g.from).dot(a) / a.squaredNorm();
      const double r = (x - g.from - std::clamp(t, 0.0, 1.0) * a).norm();
      if (t >= 0 && t <= 1) in_cylinder = std::max(in_cylinder, 0.5 * g.diameter - r);
      off_everything = std::min(off_everything, r - 0.5 * g.diameter);
    }
    for (const NetworkNode& n : layout.nodes)
      if (n.sphere_radius > 0) off_everything = std::min(off_everything, (x - n.point).norm() - n.sphere_radius);
    const WallDistance::Query q = d.closest(x);
    if (in_cylinder > sag + 1e-9) {
      EXPECT_GT(q.signed_distance, 0.0) << x.transpose();
      ++inside;
    } else if (off_everything > 0.3) {
      EXPECT_LT(q.signed_distance, 0.0) << x.transpose();
      ++outside;
    }
  }
  std::printf("network: %d points inside a cylinder, %d clear of the lumen, all on their side\n", inside, outside);
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 5000);
}
