// branches.csv's counting (scenario/branch_monitor.h) on centroids moved by hand.
#include <gtest/gtest.h>

#include <numbers>

#include "scenario/branch_monitor.h"

using namespace rbcflow;

namespace {

// A tube of radius 1 along z in a box of length 10: its mid-section at z = 5.
VesselBranch tube_branch() { return {{2, 2, 0}, {2, 2, 10}, 1.0, 0.0, 1.0}; }

StepReport with_tube_velocity(double U) {
  StepReport r;
  r.tube_velocity = U;
  return r;
}

}  // namespace

// A centroid crossing the mid-section forward counts +1, back -1; one crossing the section's
// plane outside its radius, or jumping through the box face (the minimum image turning over
// half a box from the section), counts nothing. The flow is pi a^2 U.
TEST(BranchMonitor, CountsCrossingsOfTheMidSection) {
  const Eigen::Vector3d period(0, 0, 10);
  std::vector<Eigen::Vector3d> x{{2, 2, 4.9}, {3.5, 2, 4.9}, {2, 2, 9.95}};
  BranchMonitor m({tube_branch()}, period, std::numbers::pi, x);
  x[0].z() = 5.1;   // forward through the section
  x[1].z() = 5.1;   // through the plane, 1.5 off the axis: outside the section
  x[2].z() = 10.05;  // through the box face
  std::vector<BranchRow> rows = m.update(1, 0.1, with_tube_velocity(2.0), x);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].cells_passed, 1);
  EXPECT_EQ(rows[0].cells, 3);
  EXPECT_DOUBLE_EQ(rows[0].flow_rate, 2 * std::numbers::pi);
  x[0].z() = 4.95;  // back
  EXPECT_EQ(m.update(2, 0.2, with_tube_velocity(2.0), x)[0].cells_passed, 0);
  x[0].z() = 5.0001;
  x[2].z() = 5.2;  // a jump of 5: not a step's move
  EXPECT_EQ(m.update(3, 0.3, with_tube_velocity(2.0), x)[0].cells_passed, 1);
}

// A restart continues from the counts it is given; the flows of branches that are not a tube
// are the step's section fluxes, and each cell is counted in the branch nearest it.
TEST(BranchMonitor, RestartCountsAndSectionFluxes) {
  const VesselBranch left{{2, 2, 0}, {2, 2, 10}, 1.0}, right{{6, 2, 0}, {6, 2, 10}, 1.0};
  std::vector<Eigen::Vector3d> x{{2.2, 2, 4.9}, {5.8, 2, 1}, {6.1, 2.1, 8}};
  BranchMonitor m({left, right}, Eigen::Vector3d(0, 0, 10), std::nullopt, x, {7, 3});
  x[0].z() = 5.2;
  StepReport r;
  r.section_flux = {0.25, 0.5};
  const std::vector<BranchRow> rows = m.update(11, 1.1, r, x);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].cells_passed, 8);
  EXPECT_EQ(rows[1].cells_passed, 3);
  EXPECT_EQ(rows[0].cells, 1);
  EXPECT_EQ(rows[1].cells, 2);
  EXPECT_EQ(rows[1].flow_rate, 0.5);
  EXPECT_EQ(rows[1].step, 11);
  r.section_flux = {0.25};
  EXPECT_THROW(m.update(12, 1.2, r, x), std::logic_error);
}
