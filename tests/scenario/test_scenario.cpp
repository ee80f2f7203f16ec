// prepare_scenario: the meshed lumen's volume against closed forms, the hematocrit -> count rule
// on it, listed cells checked against the wall of every vessel kind (perturbation applied), and
// the refusals that run and check share.
#include "scenario/scenario.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <utility>

#include "geometry/vessel/vessel.h"

using namespace rbcflow;

namespace {

constexpr double pi = std::numbers::pi;

// The message of the CaseError prepare_scenario throws, or "" when it accepts the case.
std::string refusal(const std::string& text) {
  try {
    prepare_scenario(parse_case(text, "s.toml"));
  } catch (const CaseError& e) {
    return e.what();
  }
  return "";
}

// A linear mesh inscribed in a round lumen of radius R with elements of size h loses the
// fraction (h / R)^2 / 6 of its cross-section (a regular polygon of edge h); twice that bounds
// the volume's relative error.
double inscribed_tolerance(double h, double radius) { return 2.0 * (h / radius) * (h / radius) / 6.0; }

const std::string kTube = "[domain]\nbox = [6.6, 6.6, 12]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = 6\n";

}  // namespace

TEST(Scenario, LumenVolumeOfATubeAndOfTheConstrictionFromTheirMeshes) {
  const Scenario tube = prepare_scenario(parse_case(kTube, "t.toml"));
  const double exact = pi * 9 * 12;
  EXPECT_NEAR(*tube.lumen_volume, exact, inscribed_tolerance(0.25, 3) * exact);
  EXPECT_LT(*tube.lumen_volume, exact);  // inscribed
  // The paper's constriction d = 3.5 - 2.2 exp(-1.2 (z - 5)^2) over [0, 10]; its volume in
  // closed form (the Gaussian's tails beyond 5 = 5.5 standard deviations are below 1e-12):
  // pi/4 (D^2 L - 2 D depth sqrt(pi/w) + depth^2 sqrt(pi/(2w))).
  const Scenario neck = prepare_scenario(parse_case(
      "[domain]\nbox = [6, 6, 10]\nmean_velocity = [0, 0, 2]\n[vessel]\nkind = \"constriction\"\n"
      "diameter = 3.5\ndepth = 2.2\nwidth = 1.2\ncenter = 5.0\nelement_size = 0.1\n",
      "c.toml"));
  const double neck_exact = pi / 4 * (3.5 * 3.5 * 10 - 2 * 3.5 * 2.2 * std::sqrt(pi / 1.2) + 2.2 * 2.2 * std::sqrt(pi / 2.4));
  EXPECT_NEAR(*neck.lumen_volume, neck_exact, inscribed_tolerance(0.1, 0.65) * neck_exact);
  EXPECT_FALSE(prepare_scenario(parse_case("[domain]\nbox = [6, 6, 10]\nmean_velocity = [0, 0, 2]\n", "n.toml"))
                   .lumen_volume);
}

TEST(Scenario, GmshMeshesATubeIntoTheNodeCountTheTestsAssume) {
  // gmsh meshes a D = 3.5, length 10 tube at h = 0.25 into 4,136 triangles, 2,068 nodes.
  const Scenario s = prepare_scenario(
      parse_case("[domain]\nbox = [6, 6, 10]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = 3.5\n", "m.toml"));
  EXPECT_NEAR(s.vessel->surface.num_points(), 2068, 0.05 * 2068);
}

TEST(Scenario, HematocritBecomesACountOnTheMeshedLumen) {
  // H = 0.15 in a D = 6, L = 12 tube: 0.15 x 339.3 / 4.18879 = 12.2 cells (12.1 in the meshed,
  // inscribed lumen); the tube hematocrit of 12 cells is then within half a cell's share of the
  // lumen of what was asked.
  const Scenario h = prepare_scenario(parse_case(kTube + "element_size = 0.5\n[cells]\nhematocrit = 0.15\norder = 8\n",
                                                 "h.toml"));
  EXPECT_EQ(h.cells.size(), 12u);
  EXPECT_NEAR(*h.tube_hematocrit, 0.15, 0.5 * (4 * pi / 3) / *h.lumen_volume);
  // Section 11.1: two cells 2 apart in a D = 3.2 tube give a tube hematocrit of about 26%.
  const Scenario pair = prepare_scenario(parse_case(
      "[domain]\nbox = [4, 4, 4]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = 3.2\n[cells]\norder = 8\n"
      "positions = [[2, 2, 1], [2, 2, 3]]\norientations = [[0, 0, 1], [0, 0, 1]]\n",
      "p.toml"));
  EXPECT_NEAR(*pair.tube_hematocrit, 0.26, 0.005);
}

// Every membrane of a run holds the rest metrics of the case's reference shape, one set for
// all: each cell's rest shape, placed at random or listed with its orientation, is a rigid
// motion of that shape, so its own metrics are the shared ones to rounding (a stretched or
// mirrored rest shape would differ at O(1)).
TEST(Scenario, MembranesShareTheRestMetricsOfTheirReferenceShape) {
  for (const std::string& cells : {std::string("hematocrit = 0.15\norder = 8\n"),
                                  std::string("order = 8\npositions = [[3.3, 3.3, 2], [3.3, 3.3, 6]]\n"
                                              "orientations = [[0, 0.6, 0.8], [1, 0, 0]]\n")}) {
    const Scenario s = prepare_scenario(parse_case(kTube + "element_size = 0.5\n[cells]\n" + cells, "r.toml"));
    ASSERT_GE(s.cells.size(), 2u) << cells;
    const std::shared_ptr<const RestMetrics>& shared = s.cells[0].membrane->rest_metrics();
    for (const Cell& c : s.cells) {
      EXPECT_EQ(c.membrane->rest_metrics(), shared);
      const RestMetrics own(c.membrane->reference(), *s.grids);
      for (auto field : {&RestMetrics::inv11, &RestMetrics::inv22, &RestMetrics::det, &RestMetrics::b11,
                         &RestMetrics::b22})  // the non-zero ones of the axisymmetric reference
        EXPECT_LT((own.*field - *shared.*field).cwiseAbs().maxCoeff(), 1e-12 * (*shared.*field).cwiseAbs().maxCoeff())
            << cells;
    }
  }
}

TEST(Scenario, ListedCellThroughTheWallOfEveryVesselKindIsRefused) {
  // A red cell (radius 1.39) lying across a D = 3 vessel (radius 1.5): on the axis it fits, 1.0
  // off it it reaches through the wall.
  auto cells = [](double x) {
    return "[cells]\norder = 8\npositions = [[" + std::to_string(x) + ", 3.0, 2.0]]\norientations = [[0, 0, 1]]\n";
  };
  const std::string box = "[domain]\nbox = [12, 6, 16]\nmean_velocity = [0, 0, 1]\n";
  const std::string bifurcation =
      box + "[vessel]\nkind = \"bifurcation\"\ndiameter = 3\ndaughter_diameters = [2.4, 2.2]\nangle_deg = 60\n"
            "center = 8\nelement_size = 0.3\n";
  const std::string constriction =
      box + "[vessel]\nkind = \"constriction\"\ndiameter = 3\ndepth = 1\nwidth = 1\ncenter = 8\nelement_size = 0.3\n";
  TubeSpec t;
  t.diameter = 3;
  t.box = Eigen::Vector3d(6, 6, 16);
  t.element_size = 0.3;
  const std::filesystem::path msh = std::filesystem::temp_directory_path() / "rbcflow_test_scenario_tube.msh";
  write_vessel(tube(t), msh.string());
  const std::string file = "[domain]\nbox = [6, 6, 16]\nmean_velocity = [0, 0, 1]\n[vessel]\nkind = \"file\"\n"
                           "path = \"" + msh.string() + "\"\n";
  for (const auto& [vessel, axis_x] : {std::pair{bifurcation, 6.0}, std::pair{constriction, 6.0}, std::pair{file, 3.0}}) {
    const std::string e = refusal(vessel + cells(axis_x - 1.0));
    EXPECT_NE(e.find("cells.positions: cell 0 at [" + std::to_string(axis_x - 1.0).substr(0, 1) +
                     ", 3, 2] crosses the vessel wall"),
              std::string::npos)
        << e;
    EXPECT_EQ(refusal(vessel + cells(axis_x)), "") << vessel;
  }
  std::filesystem::remove(msh);
}

TEST(Scenario, PerturbationIsAppliedBeforeTheWallCheck) {
  // A unit sphere on the axis of a D = 2.2 tube clears the wall by 0.1 (less the mesh's sagitta,
  // 0.2^2 / 8.8 = 0.005). Perturbed by 0.3 Y_2,2 (of unit mean square: sqrt(15/4) sin^2(theta)
  // cos(2 phi), 1.94 at its largest, on the equator, here across the axis) its surface moves 0.58
  // out through the wall.
  const std::string base =
      "[domain]\nbox = [4, 4, 6]\nmean_velocity = [0, 0, 1]\n[vessel]\ndiameter = 2.2\nelement_size = 0.2\n"
      "[cells]\nshape = \"sphere\"\norder = 8\npositions = [[2.0, 2.0, 3.0]]\norientations = [[0, 0, 1]]\n";
  EXPECT_EQ(refusal(base), "");
  EXPECT_NE(refusal(base + "perturbation = { l = 2, m = 2, amplitude = 0.3 }\n").find("crosses the vessel wall"),
            std::string::npos);
}

TEST(Scenario, ExpertEwaldOverridesAreRefusedByName) {
  EXPECT_NE(refusal(kTube + "[ewald]\nalpha = 2.0\n").find("s.toml:7: ewald.alpha: rbcflow does not take expert Ewald"),
            std::string::npos)
      << refusal(kTube + "[ewald]\nalpha = 2.0\n");
}

// Each prepare_scenario of the memory-budget tests places a tube's 16 cells (CGAL projections
// and overlap checks): ~1.3 s in Release, ~30 s under AddressSanitizer. Under the sanitizer only
// MemoryBudgetKeepsDropsOrRefuses runs (the estimate's code); the others' arithmetic over it is
// left to the Release pass.
#if defined(__SANITIZE_ADDRESS__)
#define SKIP_UNDER_SANITIZER_FOR_PLACEMENTS() \
  GTEST_SKIP() << "too slow under AddressSanitizer; run in the Release pass"
#else
#define SKIP_UNDER_SANITIZER_FOR_PLACEMENTS() \
  do {                                        \
  } while (0)
#endif

// The memory budget (memory_budget.h): the estimate grows with the cells; a budget that holds
// everything but the kept Ewald pair coefficients drops them (and the double layer's Ewald
// choice becomes the one without them); a smaller one is refused naming solver.memory_gib.
// Budgets below the estimate have the run return its freed memory, and the estimate is then
// that mode's (1.1 x the parts, lean transforms): `returned`, the run at a budget of its own
// first estimate.
TEST(Scenario, MemoryBudgetKeepsDropsOrRefuses) {
  const std::string tube = "[domain]\nbox = [6.6, 6.6, 8]\nmean_velocity = [0, 0, 1]\nviscosity_ratio = 5\n"
                           "[vessel]\ndiameter = 6\nelement_size = 0.5\n[cells]\norder = 12\nhematocrit = ";
  const Scenario few = prepare_scenario(parse_case(tube + "0.1\n", "m.toml"));
  const Scenario more = prepare_scenario(parse_case(tube + "0.3\n", "m.toml"));
  ASSERT_LT(few.cells.size(), more.cells.size());
  EXPECT_LT(few.memory.total(), more.memory.total());
  EXPECT_TRUE(more.keeps_pair_coefficients);
  ASSERT_GT(more.memory.kept_coefficients, 0);
  EXPECT_EQ(more.memory.parts.size(), 7u);  // geometry, singular, nearly singular, Ewald, wall, recycled space, coupling

  constexpr double gib = 1024.0 * 1024.0 * 1024.0;
  const Scenario returned = prepare_scenario(
      parse_case(tube + "0.3\n[solver]\nmemory_gib = " + std::to_string(more.memory.total() / gib) + "\n", "m.toml"));
  ASSERT_FALSE(returned.reuses_freed_memory);
  ASSERT_TRUE(returned.keeps_pair_coefficients);
  EXPECT_EQ(returned.memory.peak_factor, MemoryEstimate::kPeakFactorReturned);
  EXPECT_NEAR(returned.memory.parts_total(), more.memory.parts_total() - more.memory.lean_transforms,
              1e-9 * more.memory.parts_total());
  const double without = returned.memory.total() - MemoryEstimate::kPeakFactorReturned * more.memory.kept_coefficients;
  const double between = 0.5 * (without + returned.memory.total()) / gib;
  const Scenario tight = prepare_scenario(parse_case(tube + "0.3\n[solver]\nmemory_gib = " + std::to_string(between) + "\n", "m.toml"));
  EXPECT_FALSE(tight.keeps_pair_coefficients);
  EXPECT_EQ(tight.options.domain.max_kept_pairs, 0);
  // Its estimate (what rbcflow check prints) is of the run as chosen: no kept coefficients,
  // within the budget.
  EXPECT_EQ(tight.memory.kept_coefficients, 0.0);
  EXPECT_LE(tight.memory.total(), between * gib);
  const EwaldSum& dl = tight.ewald[1];
  ASSERT_EQ(dl.what, "cells, double layer");
  const EwaldChoice unkept = choose_ewald_parameters(EwaldKernel::stresslet, 1e-6, PeriodicBox(Eigen::Vector3d(6.6, 6.6, 8)),
                                                     dl.nodes, dl.nodes, RealSpaceUse{});
  EXPECT_EQ(dl.choice.parameters.grid, unkept.parameters.grid);
  EXPECT_EQ(dl.choice.parameters.cutoff, unkept.parameters.cutoff);

  const std::string e = refusal(tube + "0.3\n[solver]\nmemory_gib = " + std::to_string(0.5 * without / gib) + "\n");
  EXPECT_NE(e.find("solver.memory_gib: the run needs about"), std::string::npos) << e;
  EXPECT_NE(e.find("use fewer cells"), std::string::npos) << e;
}

// A run far below its budget keeps what its steps free for the next steps; one above 3/4 of it
// returns it (libsolver/stepper/step_memory.h), with or without the kept pair coefficients, and
// transforms its double layer lean: its estimate's parts lowered by an array of 2 grids of 3,
// their factor 1.1 instead of 1.3.
TEST(Scenario, FreedMemoryIsKeptOnlyFarBelowTheBudget) {
  SKIP_UNDER_SANITIZER_FOR_PLACEMENTS();
  const std::string tube = "[domain]\nbox = [6.6, 6.6, 8]\nmean_velocity = [0, 0, 1]\nviscosity_ratio = 5\n"
                           "[vessel]\ndiameter = 6\nelement_size = 0.5\n[cells]\norder = 12\nhematocrit = 0.3\n";
  constexpr double gib = 1024.0 * 1024.0 * 1024.0;
  const double total = prepare_scenario(parse_case(tube, "m.toml")).memory.total();
  const auto with_budget = [&](double fraction) {
    return prepare_scenario(parse_case(tube + "[solver]\nmemory_gib = " + std::to_string(total / fraction / gib) + "\n",
                                       "m.toml"));
  };
  const Scenario far = with_budget(0.7);
  EXPECT_TRUE(far.reuses_freed_memory);
  EXPECT_FALSE(far.options.domain.lean_transforms);
  const Scenario close = with_budget(0.8);
  EXPECT_FALSE(close.reuses_freed_memory);
  EXPECT_TRUE(close.keeps_pair_coefficients);
  EXPECT_TRUE(close.options.domain.lean_transforms);
  ASSERT_GT(far.memory.lean_transforms, 0.0);
  EXPECT_EQ(far.memory.peak_factor, MemoryEstimate::kPeakFactorKept);
  EXPECT_EQ(close.memory.peak_factor, MemoryEstimate::kPeakFactorReturned);
  EXPECT_NEAR(far.memory.parts_total() - close.memory.parts_total(), far.memory.lean_transforms,
              1e-9 * far.memory.parts_total());
  const double program = far.memory.total() - MemoryEstimate::kPeakFactorKept * far.memory.parts_total();
  EXPECT_NEAR(close.memory.total(), MemoryEstimate::kPeakFactorReturned * close.memory.parts_total() + program,
              1e-9 * total);
  // Fits only without the kept coefficients: a budget 2% under the lean estimate.
  const Scenario over = with_budget(1.02 * total / close.memory.total());
  EXPECT_FALSE(over.keeps_pair_coefficients);
  EXPECT_FALSE(over.reuses_freed_memory);
}

// On P ranks (rbcflow check --ranks P) each rank holds its share of the split parts and all of
// the repeated ones, and the ranks on one machine share its memory: a budget that one process
// fits can be too small for two ranks on the same machine, and the refusal says per rank.
TEST(Scenario, MemoryBudgetOfRanksSharingAMachine) {
  SKIP_UNDER_SANITIZER_FOR_PLACEMENTS();
  const std::string tube = "[domain]\nbox = [6.6, 6.6, 8]\nmean_velocity = [0, 0, 1]\nviscosity_ratio = 5\n"
                           "[vessel]\ndiameter = 6\nelement_size = 0.5\n[cells]\norder = 12\nhematocrit = 0.3\n";
  const Scenario one = prepare_scenario(parse_case(tube, "m.toml"));
  const Scenario two = prepare_scenario(parse_case(tube, "m.toml"), 2);
  EXPECT_EQ(one.memory.ranks, 1);
  EXPECT_EQ(two.memory.ranks, 2);
  EXPECT_EQ(two.ranks_per_machine, 2);
  EXPECT_NEAR(two.memory_budget, 0.5 * one.memory_budget, 1e-9 * one.memory_budget);
  ASSERT_EQ(one.memory.parts.size(), two.memory.parts.size());
  for (std::size_t i = 0; i < one.memory.parts.size(); ++i) {
    const MemoryEstimate::Part& p = two.memory.parts[i];
    EXPECT_EQ(p.bytes, one.memory.parts[i].bytes) << p.name;  // the same run, on one process
    EXPECT_LE(two.memory.on_each_rank(p), p.bytes) << p.name;
    EXPECT_GE(two.memory.on_each_rank(p), 0.5 * p.bytes) << p.name;
  }
  // Each rank holds more than half a process (what is repeated), less than a whole one.
  const double per_rank = two.memory.total();
  EXPECT_LT(per_rank, one.memory.total());
  EXPECT_GT(2 * per_rank, one.memory.total());

  // Near the budget the runs return their freed memory: the estimates of that mode, each run
  // at a budget of its own first estimate.
  constexpr double gib = 1024.0 * 1024.0 * 1024.0;
  const Scenario one_returned = prepare_scenario(
      parse_case(tube + "[solver]\nmemory_gib = " + std::to_string(one.memory.total() / gib) + "\n", "m.toml"));
  const Scenario two_returned = prepare_scenario(
      parse_case(tube + "[solver]\nmemory_gib = " + std::to_string(2 * per_rank / gib) + "\n", "m.toml"), 2);
  ASSERT_FALSE(one_returned.reuses_freed_memory);
  ASSERT_FALSE(two_returned.reuses_freed_memory);
  const double without_two =
      two_returned.memory.total() - MemoryEstimate::kPeakFactorReturned * two.memory.kept_coefficients / 2;
  ASSERT_LT(one_returned.memory.total(), 2 * without_two);
  const std::string budget = std::to_string(0.5 * (one_returned.memory.total() + 2 * without_two) / gib);
  const Case fits_one = parse_case(tube + "[solver]\nmemory_gib = " + budget + "\n", "m.toml");
  EXPECT_TRUE(prepare_scenario(fits_one).keeps_pair_coefficients);
  try {
    prepare_scenario(fits_one, 2);
    ADD_FAILURE() << "two ranks on one machine with " << budget << " GiB were not refused";
  } catch (const CaseError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("solver.memory_gib: the run needs about"), std::string::npos) << what;
    EXPECT_NE(what.find("on each of its ranks"), std::string::npos) << what;
    EXPECT_NE(what.find("per rank (solver.memory_gib shared by 2 ranks)"), std::string::npos) << what;
    EXPECT_NE(what.find("fewer ranks on each machine"), std::string::npos) << what;
  }
}
