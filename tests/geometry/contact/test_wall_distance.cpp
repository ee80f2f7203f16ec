#include "geometry/contact/wall_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

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
