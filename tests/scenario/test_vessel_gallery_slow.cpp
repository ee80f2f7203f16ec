// The junction balance of the gallery's network at a fine wall (label slow): the wall's
// collocation leak falls at second order in h / r, to below 1e-3 of the parent's flow at
// h = 0.12 (h / r = 0.06 .. 0.08; test_vessel_gallery holds h = 0.3 to 5e-3), without cells and
// with the gallery's 11 cells at N = 12 (each branch measured through its section clearest of
// them, section_flux.h).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <vector>

#include "geometry/vessel/network.h"
#include "io/case.h"
#include "scenario/scenario.h"

using namespace rbcflow;

namespace {

// The flows of the network's six segments after one step: split 0 -> (1, 2), merge (3, 4) -> 5,
// bends 1 -> 3 and 2 -> 4; each imbalance relative to the parent's flow.
void expect_balanced(const std::vector<double>& q, const char* what, int nodes) {
  ASSERT_EQ(q.size(), 6u);
  const double split = (q[0] - q[1] - q[2]) / q[0], merge = (q[3] + q[4] - q[5]) / q[0];
  const double bend1 = (q[1] - q[3]) / q[0], bend2 = (q[2] - q[4]) / q[0];
  std::printf("%s, h = 0.12, %d wall nodes: flows %.6f %.6f %.6f %.6f %.6f %.6f; imbalance split %.2e, merge %.2e, "
              "bends %.2e %.2e\n", what, nodes, q[0], q[1], q[2], q[3], q[4], q[5], split, merge, bend1, bend2);
  for (double imbalance : {split, merge, bend1, bend2}) EXPECT_LT(std::abs(imbalance), 1e-3);
}

Case fine_network() {
  Case c = read_case(std::filesystem::path(RBCFLOW_VESSELS_DIR) / "network.toml");
  c.vessel->element_size = 0.12;
  return c;
}

}  // namespace

TEST(VesselGalleryFine, NetworkJunctionsBalanceTo1e3) {
  Case c = fine_network();
  c.cells.reset();
  Scenario s = prepare_scenario(c);
  std::unique_ptr<CellStepper> stepper = make_stepper(s);
  expect_balanced(stepper->step().section_flux, "without cells", s.vessel->surface.num_points());
}

TEST(VesselGalleryFine, NetworkJunctionsBalanceTo1e3WithCells) {
  Case c = fine_network();
  c.cells->order = 12;
  c.cells->dealias = 2;
  Scenario s = prepare_scenario(c);
  std::unique_ptr<CellStepper> stepper = make_stepper(s);
  expect_balanced(stepper->step().section_flux, "11 cells at N = 12", s.vessel->surface.num_points());
}
