// Derived parameters: the dt limit (37), vessel volume and area, cell counts, memory model.
#include "io/case_derived.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

using namespace rbcflow;

namespace {

Case tube_case(double diameter, double length, const std::string& cells) {
  return parse_case("[domain]\nbox = [6.6, 6.6, " + std::to_string(length) +
                        "]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = " + std::to_string(diameter) +
                        "\n" + cells,
                    "t.toml");
}

}  // namespace

TEST(CaseDerived, TimeStepLimitIsEquation37) {
  CaseCells rbc;  // N = 16, Ed = 200, Eb = 0.0669, A = 16.8
  // h = sqrt(16.8) / 16 = 0.256174; the dilatation term 2.5 h^1.2 / 200 = 2.43866e-3 limits
  // (bending: 0.19 h^3.2 / 0.0669 = 3.64e-2).
  EXPECT_NEAR(effective_spacing(rbc), 0.256174, 1e-6);
  EXPECT_NEAR(time_step_limit(rbc), 2.43866e-3, 1e-8);
  // Section 7: the two limits of (37) are equal near h_eff = 0.066, i.e. N = 62.
  rbc.order = 62;
  const double h = effective_spacing(rbc);
  const double dilatation = 2.5 * std::pow(h, 1.2) / 200, bending = 0.19 * std::pow(h, 3.2) / 0.0669;
  EXPECT_NEAR(dilatation / bending, 1.0, 0.05);
  EXPECT_EQ(time_step_limit(rbc), std::min(dilatation, bending));
  // No bending: only the dilatation term.
  rbc.membrane.bending_modulus = 0;
  EXPECT_EQ(time_step_limit(rbc), dilatation);
}

TEST(CaseDerived, TimeStepIsAutoOrGiven) {
  const Case c = tube_case(3, 10, "[cells]\n[time]\ndt_safety = 0.25\n");
  EXPECT_DOUBLE_EQ(time_step(c), 0.25 * time_step_limit(*c.cells));
  const Case fixed = tube_case(3, 10, "[cells]\n[time]\ndt = 1e-3\n");
  EXPECT_EQ(time_step(fixed), 1e-3);
  const Case walls_only = tube_case(3, 10, "[time]\nend = 2\n");
  EXPECT_EQ(time_step(walls_only), 2.0);
}

TEST(CaseDerived, ReferenceCellOfOtherShapesIsMeasured) {
  CaseCells sphere;
  sphere.shape = CellShape::sphere;
  EXPECT_NEAR(reference_cell(sphere).area, 4 * std::numbers::pi, 1e-10);
  EXPECT_NEAR(reference_cell(sphere).volume, 4 * std::numbers::pi / 3, 1e-10);
  EXPECT_EQ(reference_cell(CaseCells{}).area, 16.8);
}

TEST(CaseDerived, VesselVolumeAndArea) {
  const Case tube = tube_case(6, 12, "");
  EXPECT_NEAR(*vessel_volume(tube), std::numbers::pi * 9 * 12, 1e-9);
  EXPECT_NEAR(*vessel_wall_area(tube), std::numbers::pi * 6 * 12, 1e-9);
  // The paper's constriction: d = 3.5 - 2.2 exp(-1.2 (z - 5)^2) over [0, 10]. Its volume in
  // closed form (the Gaussian's tails beyond 5 = 5.5 standard deviations are below 1e-12):
  // pi/4 (D^2 L - 2 D depth sqrt(pi/w) + depth^2 sqrt(pi/(2w))).
  const Case neck = parse_case(
      "[domain]\nbox = [6, 6, 10]\nmean_velocity = [0, 0, 2]\n[vessel]\nkind = \"constriction\"\n"
      "diameter = 3.5\ndepth = 2.2\nwidth = 1.2\ncenter = 5.0\n",
      "c.toml");
  const double pi = std::numbers::pi;
  const double exact = pi / 4 * (3.5 * 3.5 * 10 - 2 * 3.5 * 2.2 * std::sqrt(pi / 1.2) + 2.2 * 2.2 * std::sqrt(pi / 2.4));
  EXPECT_NEAR(*vessel_volume(neck), exact, 1e-9 * exact);
  EXPECT_LT(*vessel_wall_area(neck), pi * 3.5 * 10);
  const Case none = parse_case("[domain]\nbox = [6, 6, 10]\nmean_velocity = [0, 0, 2]\n", "n.toml");
  EXPECT_FALSE(vessel_volume(none));
}

TEST(CaseDerived, CellCountAndHematocrit) {
  // Section 11.1: two cells 2 apart in a D = 3.2 tube give a tube hematocrit of about 26%.
  const Case pair = tube_case(3.2, 4, "[cells]\ncount = 2\n");
  EXPECT_EQ(*cell_count(pair), 2);
  EXPECT_NEAR(*tube_hematocrit(pair, 2), 0.26, 0.005);
  // H = 0.3 in a D = 6, L = 12 tube: 0.3 * 339.29 / 4.18879 = 24.3 cells.
  const Case h = tube_case(6, 12, "[cells]\nhematocrit = 0.3\n");
  EXPECT_EQ(*cell_count(h), 24);
  EXPECT_EQ(*cell_count(tube_case(6, 12, "")), 0);
}

TEST(CaseDerived, MemoryModelCountsWallNodesLikeGmsh) {
  // STACK.md: gmsh meshes a D = 3.5, length 10 tube at h = 0.25 into 4,136 triangles, about
  // 2,068 nodes; the estimate from the area is within 5% of that.
  const Case c = parse_case(
      "[domain]\nbox = [6, 6, 10]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = 3.5\n[cells]\n", "m.toml");
  const MemoryEstimate m = memory_estimate(c, 1);
  ASSERT_TRUE(m.wall_nodes);
  EXPECT_NEAR(*m.wall_nodes, 2068, 0.05 * 2068);
  EXPECT_GT(m.cells, 0);
  EXPECT_DOUBLE_EQ(memory_estimate(c, 10).cells, 10 * m.cells);
  EXPECT_EQ(m.ewald, 0);  // the grid is the solver's choice unless given
  EXPECT_EQ(m.total(), m.cells + m.wall);
}

TEST(CaseDerived, FlowAxisFollowsVesselFlowOrForce) {
  EXPECT_EQ(flow_axis(tube_case(3, 10, "")), 2);
  EXPECT_EQ(flow_axis(parse_case("[domain]\nbox = [4, 4, 4]\nmean_velocity = [0, -2, 1]\n", "a.toml")), 1);
  EXPECT_EQ(flow_axis(parse_case("[domain]\nbox = [4, 4, 4]\npressure_gradient = [3, 0, 0]\n", "a.toml")), 0);
  EXPECT_EQ(flow_axis(parse_case("[domain]\nbox = [4, 4, 4]\nmean_velocity = [0, 0, 0]\n[cells]\n"
                                 "body_force = [0, 1, 0]\n",
                                 "a.toml")),
            1);
  EXPECT_EQ(flow_axis(parse_case("[domain]\nkind = \"free\"\nbackground_flow = { kind = \"shear\" }\n", "a.toml")), 0);
  EXPECT_EQ(flow_axis(parse_case("[domain]\nbox = [4, 4, 4]\nmean_velocity = [0, 0, 0]\n", "a.toml")), 2);
}
