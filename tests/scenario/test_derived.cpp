// Derived parameters of a case alone: the dt limit (37), the reference cell, the memory model,
// the flow axis. (Lumen volume and cell counts come from the meshed vessel: test_scenario.cpp.)
#include "scenario/derived.h"

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

TEST(CaseDerived, NeoHookeanLimitTakesTheAreaModulus) {
  // The neo-Hookean law has no E_D: (37) takes its area-dilatation modulus K_S = 3 E_S (with
  // E_S = 10: 2.5 h^1.2 / 30), the step at which data/cases/capsule_shear.toml stays stable
  // (run.capsule_shear_example_stays_stable).
  CaseCells capsule;
  capsule.shape = CellShape::sphere;
  capsule.membrane.law = MembraneLawKind::neo_hookean;
  capsule.membrane.shear_modulus = 10;
  capsule.membrane.bending_modulus = 0;
  const double h = effective_spacing(capsule);
  EXPECT_NEAR(h, std::sqrt(4 * std::numbers::pi) / 16, 1e-10);
  EXPECT_DOUBLE_EQ(time_step_limit(capsule), 2.5 * std::pow(h, 1.2) / 30);
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
