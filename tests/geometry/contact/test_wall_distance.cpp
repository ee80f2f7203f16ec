#include "geometry/contact/wall_distance.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

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
