// Every vessel of the gallery data/vessels/ (one test per case file: adding a vessel adds its
// test): the wall is built and checked, its cell-free flow solved, the flux compared across each
// branch's cross-sections and balanced at its junctions, and its cells (placed at H_T = 0.15)
// stepped three times with their volumes kept.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <filesystem>
#include <string>
#include <vector>

#include "geometry/vessel/network.h"
#include "geometry/vessel/vessel_branch.h"
#include "io/case.h"
#include "scenario/scenario.h"

using namespace rbcflow;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> gallery() {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(RBCFLOW_VESSELS_DIR))
    if (e.path().extension() == ".toml") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

Case gallery_case(const std::string& name) { return read_case(fs::path(RBCFLOW_VESSELS_DIR) / (name + ".toml")); }

// Junction balances of a branch set: bifurcation parent = daughters; a network's inflow =
// outflow at every junction (flows are along each segment from `from` to `to`). Relative to
// the largest flow.
std::vector<double> junction_imbalances(const Case& c, const std::vector<double>& q) {
  const double largest = *std::max_element(q.begin(), q.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
  std::vector<double> out;
  if (c.vessel->kind == VesselKind::bifurcation) out.push_back((q[0] - q[1] - q[2]) / std::abs(largest));
  if (c.vessel->kind == VesselKind::network) {
    NetworkSpec spec;
    for (const CaseSegment& g : c.vessel->segments)
      spec.segments.push_back({Eigen::Vector3d(g.from[0], g.from[1], g.from[2]), Eigen::Vector3d(g.to[0], g.to[1], g.to[2]),
                               g.diameter});
    spec.axis = c.vessel->axis;
    spec.box = Eigen::Vector3d(c.domain.box[0], c.domain.box[1], c.domain.box[2]);
    spec.element_size = c.vessel->element_size;
    const NetworkLayout l = network_layout(spec);
    for (int n = 0; n < static_cast<int>(l.nodes.size()); ++n) {
      if (l.nodes[n].on_face) continue;
      double balance = 0;
      for (int i = 0; i < static_cast<int>(l.ends.size()); ++i) {
        if (l.ends[i][1] == n) balance += q[i];
        if (l.ends[i][0] == n) balance -= q[i];
      }
      out.push_back(balance / std::abs(largest));
    }
  }
  return out;
}

class VesselGallery : public ::testing::TestWithParam<std::string> {};

}  // namespace

// The cell-free flow: the wall's GMRES converges; every candidate section of a branch carries
// the same flux to 1e-3 (a straight piece of vessel; the sections sit where the branch is its
// own); junctions balance within the wall's leak. The wall's linear elements hold no-slip at
// their nodes only, so flux leaks through the wall at second order in h / r: measured on
// data/cases/network.toml 2.0e-3, 2.6e-3 and 6.5e-4 of the parent's flow at h = 0.3, 0.2, 0.1
// (h / r = 0.2 .. 0.07); the gallery's bifurcation and network at h = 0.3 (h / r = 0.15 .. 0.2)
// are held to 5e-3, and the slow VesselGalleryFine test holds the network to 1e-3 at h = 0.12.
TEST_P(VesselGallery, CellFreeFlowIsConservedThroughEveryBranch) {
  Case c = gallery_case(GetParam());
  c.cells.reset();
  Scenario s = prepare_scenario(c);
  ASSERT_TRUE(s.vessel);
  EXPECT_GT(*s.lumen_volume, 0.0);
  // Each candidate section of each branch measured as a branch of its own.
  std::vector<int> branch_of;
  s.options.flux_sections.clear();
  for (int b = 0; b < static_cast<int>(s.branches.size()); ++b) {
    for (SectionQuadrature& q : candidate_sections(s.branches[b])) {
      s.options.flux_sections.push_back({std::move(q)});
      branch_of.push_back(b);
    }
  }
  std::unique_ptr<CellStepper> stepper = make_stepper(s);
  const StepReport r = stepper->step();
  EXPECT_LT(r.wall_residual, c.solver.gmres_tolerance);
  EXPECT_GT(r.gmres_wall, 0);
  std::printf("%s: %d wall nodes, lumen %.4g, wall GMRES %d iterations (residual %.2e)\n", GetParam().c_str(),
              s.vessel->surface.num_points(), *s.lumen_volume, r.gmres_wall, r.wall_residual);
  if (s.branches.empty()) return;  // a vessel from a file: its branches are not known
  std::vector<double> mean(s.branches.size(), 0.0);
  std::vector<int> count(s.branches.size(), 0);
  for (std::size_t k = 0; k < branch_of.size(); ++k) {
    mean[branch_of[k]] += r.section_flux[k];
    ++count[branch_of[k]];
  }
  for (std::size_t b = 0; b < mean.size(); ++b) mean[b] /= count[b];
  for (std::size_t k = 0; k < branch_of.size(); ++k) {
    const int b = branch_of[k];
    EXPECT_NEAR(r.section_flux[k], mean[b], 1e-3 * std::abs(mean[b])) << "branch " << b << ", section " << k;
  }
  for (std::size_t b = 0; b < mean.size(); ++b) std::printf("  branch %zu: flow %.6f (%d sections)\n", b, mean[b], count[b]);
  for (double imbalance : junction_imbalances(c, mean)) {
    std::printf("  junction imbalance %.2e of the largest flow\n", imbalance);
    EXPECT_LT(std::abs(imbalance), 5e-3);
  }
}

// The cells, placed at H_T = 0.15 inside the lumen and clear of the wall, take three steps with
// every volume kept to 1e-6 (the volume constraint) and branches.csv's flows reported.
TEST_P(VesselGallery, CellsPlacedAtAHematocritTakeThreeSteps) {
  const Case c = gallery_case(GetParam());
  Scenario s = prepare_scenario(c);
  ASSERT_FALSE(s.cells.empty());
  ASSERT_TRUE(s.tube_hematocrit);
  EXPECT_NEAR(*s.tube_hematocrit, 0.15, 0.03);
  std::unique_ptr<CellStepper> stepper = make_stepper(s);
  for (int step = 0; step < 3; ++step) {
    const StepReport r = stepper->step();
    EXPECT_LT(r.max_volume_error, 1e-6);
    ASSERT_TRUE(r.min_wall_gap);
    EXPECT_GT(*r.min_wall_gap, 0.0);
    if (!s.branch_flow_by_meter) {
      EXPECT_EQ(r.section_flux.size(), s.branches.size());
    }
  }
  std::printf("%s: %zu cells, H_T %.3f, three steps\n", GetParam().c_str(), stepper->cells().size(), *s.tube_hematocrit);
}

INSTANTIATE_TEST_SUITE_P(Gallery, VesselGallery, ::testing::ValuesIn(gallery()),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

// The gallery's bifurcation driven by its parent's mean velocity (tube_velocity, held every
// step by the tube meter with the section in the parent's middle): the held U is exact, and
// the parent's flux measured independently through its clearest section (section_flux.h)
// agrees with pi a^2 U to the meter's calibration (U as half the cell-free axis velocity, the
// parent only two diameters long between its junction spheres: 0.91% low cell-free at
// h = 0.3) plus the section's error near the cells (up to 0.5%, test_section_flux): bound
// 1.5% (measured 1.05% and 0.56% at steps 1 and 2).
TEST(VesselGalleryDrive, BifurcationParentVelocityIsHeld) {
  Case c = gallery_case("bifurcation");
  c.domain.mean_velocity.reset();
  c.domain.tube_velocity = 2.0;
  Scenario s = prepare_scenario(c);
  ASSERT_FALSE(s.branch_flow_by_meter);
  std::unique_ptr<CellStepper> stepper = make_stepper(s);
  const double target = std::numbers::pi * 4.0 * 2.0;  // pi a^2 U, a = 2
  for (int step = 0; step < 2; ++step) {
    const StepReport r = stepper->step();
    ASSERT_TRUE(r.tube_velocity);
    EXPECT_NEAR(*r.tube_velocity, 2.0, 1e-9);
    EXPECT_FALSE(r.discharge_hematocrit);  // the cells are not all in the parent
    ASSERT_EQ(r.section_flux.size(), 3u);
    std::printf("step %d: <u> %.5f, parent flux %.5f (pi a^2 U %.5f), daughters %.5f + %.5f\n", step + 1,
                r.mean_velocity.z(), r.section_flux[0], target, r.section_flux[1], r.section_flux[2]);
    EXPECT_NEAR(r.section_flux[0], target, 0.015 * target);
  }
}
