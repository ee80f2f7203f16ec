#include <gtest/gtest.h>

#include <limits>

#include "libsolver/common/periodic_box.h"

using namespace rbcflow;

TEST(PeriodicBox, WrapsIntoTheBox) {
  const PeriodicBox box(Eigen::Vector3d(1.0, 2.0, 0.5));
  EXPECT_DOUBLE_EQ(box.volume(), 1.0);
  const Eigen::Vector3d w = box.wrap(Eigen::Vector3d(-0.25, 4.5, 1.75));
  EXPECT_NEAR(w[0], 0.75, 1e-15);
  EXPECT_NEAR(w[1], 0.5, 1e-15);
  EXPECT_NEAR(w[2], 0.25, 1e-15);
  // Just below a multiple of L rounds to L: wrapped to 0, never L.
  const Eigen::Vector3d edge = box.wrap(Eigen::Vector3d(-1e-18, 2.0, 0.5));
  for (int d = 0; d < 3; ++d) {
    EXPECT_GE(edge[d], 0.0);
    EXPECT_LT(edge[d], box.length(d));
  }
}

TEST(PeriodicBox, RejectsDegenerateBoxes) {
  EXPECT_THROW(PeriodicBox(Eigen::Vector3d(1.0, 0.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(PeriodicBox(Eigen::Vector3d(1.0, -2.0, 1.0)), std::invalid_argument);
  EXPECT_THROW(PeriodicBox(Eigen::Vector3d(1.0, 1.0, std::numeric_limits<double>::infinity())),
               std::invalid_argument);
}
