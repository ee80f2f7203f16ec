// The junction balance of the gallery's network at a fine wall (label slow): the wall's
// collocation leak falls at second order in h / r, to below 1e-3 of the parent's flow at
// h = 0.12 (h / r = 0.06 .. 0.08; test_vessel_gallery holds h = 0.3 to 5e-3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "geometry/vessel/network.h"
#include "io/case.h"
#include "scenario/scenario.h"

using namespace rbcflow;

TEST(VesselGalleryFine, NetworkJunctionsBalanceTo1e3) {
  Case c = read_case(std::filesystem::path(RBCFLOW_VESSELS_DIR) / "network.toml");
  c.cells.reset();
  c.vessel->element_size = 0.12;
  Scenario s = prepare_scenario(c);
  std::unique_ptr<CellStepper> stepper = make_stepper(s);
  const StepReport r = stepper->step();
  ASSERT_EQ(r.section_flux.size(), 6u);
  const std::vector<double>& q = r.section_flux;
  // Segments 0 -> (1, 2) at the split, (3, 4) -> 5 at the merge; 1 -> 3 and 2 -> 4 at the bends.
  const double split = (q[0] - q[1] - q[2]) / q[0], merge = (q[3] + q[4] - q[5]) / q[0];
  const double bend1 = (q[1] - q[3]) / q[0], bend2 = (q[2] - q[4]) / q[0];
  std::printf("h = 0.12, %d wall nodes: flows %.6f %.6f %.6f %.6f %.6f %.6f; imbalance split %.2e, merge %.2e, "
              "bends %.2e %.2e\n", s.vessel->surface.num_points(), q[0], q[1], q[2], q[3], q[4], q[5], split, merge,
              bend1, bend2);
  for (double imbalance : {split, merge, bend1, bend2}) EXPECT_LT(std::abs(imbalance), 1e-3);
}
