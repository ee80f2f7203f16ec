// Constriction (paper section 10.2; issue 7 validation 6), the full run: one red cell
// (N = 12, M = 24, lambda = 1, parameters (35)) from z = 3.25, 0.25 off the axis, driven at
// tube velocity 2 (<u> from tube_drive.h) through the D = 3.5 -> 1.3 neck at z = 5, to t = 2
// with dt half the limit (37) (1,162 steps), on a wall of element size 0.3 (the paper's 25,804
// triangles would be h ~ 0.1). With the volume constraint the run must stay stable (finite,
// inside the vessel, no blow-up), hold the volume to 1e-4 every step, and carry the cell
// through the neck (its centroid past z = 6 by t = 2, as in the paper's Figs. 6-7, where the
// rib-like buckling forms in the neck at t ~ 0.9); the same run without the constraint is
// reported (the paper's N = 16 run drifted to -0.5%, Fig. 9) and must stay below the 1%
// blow-up limit. test_constriction.cpp is the default-suite version.
// Measured (commit b1223ea, 1 thread beside other jobs, 3,948 s + 1,727 s): <u> = 13.50 for
// tube velocity 2 (ratio 0.148 on this wall); PASS. The cell goes through the neck (centroid
// z 3.25 -> 9.80 by t = 2; max r / R(z) 0.957); constrained max |V/V0 - 1| = 2.9e-11; without
// the constraint V/V0 - 1 rises to +2.5e-4, falls to -9.1e-3 in the neck and ends at -5.6e-3,
// the course of the paper's Fig. 9 (up slightly, then down to 99.5%); area error <= 5.2e-2.
#include <gtest/gtest.h>

#include "constriction_support.h"

using namespace rbcflow;
using namespace rbcflow::constriction_test;

namespace {
constexpr int kN = 12, kM = 24;
constexpr double kElementSize = 0.3, kEnd = 2.0;
}  // namespace

TEST(ConstrictionSlow, StableToTimeTwoWithVolumeHeld) {
  const double dt = 0.5 * time_step_limit(kN);
  const long steps = std::lround(std::ceil(kEnd / dt - 1e-9));
  const ConstrictionRun on = run_constriction(kN, kM, kElementSize, dt, steps, true, 50);
  ASSERT_FALSE(on.blew_up) << on.error;
  EXPECT_TRUE(on.finite);
  EXPECT_GE(on.time, kEnd - 1e-9);
  EXPECT_LE(on.max_volume_error, 1e-4);
  EXPECT_LT(on.max_wall_fraction, 1.0) << "a node left the vessel";
  EXPECT_GT(on.end.z(), 6.0) << "the cell should have passed the neck at z = 5";

  const ConstrictionRun off = run_constriction(kN, kM, kElementSize, dt, steps, false, 50);
  ASSERT_FALSE(off.blew_up) << off.error;
  EXPECT_TRUE(off.finite);
  EXPECT_LT(off.max_volume_error, 1e-2);
  std::printf("t = %.3f (%ld steps): max volume error constrained %.3e, unconstrained %.3e (range %+.3e .. %+.3e, "
              "final %+.3e); centroid z %.3f -> %.3f; %.0f s + %.0f s\n",
              on.time, on.steps, on.max_volume_error, off.max_volume_error, off.min_volume_change,
              off.max_volume_change, off.final_volume_change, on.start.z(), on.end.z(), on.seconds, off.seconds);
}
