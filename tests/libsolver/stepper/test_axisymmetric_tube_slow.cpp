// Axisymmetric tube flow (paper section 11.1, Figs. 10-11; issue 7 validation 5), the curve:
// a red cell on the axis of a D = 3.2 tube, one per period 2, lambda = 5, membrane (35),
// N = 8 with factor-three de-aliasing (M = 24), wall h = 0.3, at the paper's tube velocities
// 0.62, 1.25, 2.52, 5.09 and 7.66, each from the resting cell with dt half the limit (37)
// and the volume constraint of section 10.2, until steady: the membrane's motion relative to
// the centroid (max over the nodes of |u - u_mean| / |u_mean|; zero for the pure translation
// of the steady state) below 2% AND mu_eff / mu_0 changed by less than 2e-3 over the last 0.25
// time units, at most to t = 8.
// Measured with the slip criterion alone and no volume constraint (commit 93e684b, 2,984 s on
// 1 thread beside other jobs; cell-free mu_eff = 1.00026):
//   U target  U_tube  mu_eff/mu_0  change over last 0.25  t at stop  steps  max |V/V0 - 1|
//   0.62      0.590   1.52732      3.2e-3                 6.17       2201   1.9e-3
//   1.25      1.227   1.43724      8.3e-3                 3.63       1297   3.7e-3
//   2.52      2.546   1.35577      2.4e-2                 2.18        778   6.6e-3
//   5.09      5.275   1.28569      5.1e-2                 1.24        441   8.0e-3
//   7.66      8.111   1.22770      9.9e-2                 0.91        325   9.0e-3
// decreasing at every step, but the test failed: at the fast flows the slip (relative to the
// large translation speed) falls below 2% long before mu_eff settles (still -0.1 per 0.25 at
// U = 7.66), so the 5.09 -> 7.66 step (0.058) was smaller than the transient left; and the
// unconstrained volume drift grew with U towards the 1% limit. Hence the mu_eff criterion and
// the volume constraint. That version (commit 8e5ceb6, 1 thread beside other jobs) was stopped
// during the fourth velocity after 1.4 h:
//   U target  U_tube  mu_eff/mu_0  t at stop  steps
//   0.62      0.590   1.52945      6.17       2201
//   1.25      1.242   1.40391      5.30       1891
//   2.52      2.687   1.20917      6.70       2391
//   5.09      5.94    0.97967      6.72       2400 (stopped; still falling ~0.04 per unit time)
// Decreasing with U, but after the shape has settled (length and radius constant to 1e-3)
// mu_eff keeps drifting down at a steady rate (-0.025 per unit time at U = 2.52, -0.04 at
// 5.09) while the cell creeps off the axis (offset 7.5e-5 -> 7.5e-3) and the membrane still
// slides (slip ~1%), and at U = 5.09 it falls below the plasma's (unphysical). Suspected: the
// N = 8 resolution over long runs. The test fails; see the issue notes.
#include <gtest/gtest.h>

#include "axisymmetric_tube_support.h"

using namespace rbcflow;
using namespace rbcflow::tube_test;

namespace {
constexpr int kN = 8, kM = 24;
constexpr double kElementSize = 0.3, kMaxEnd = 8.0, kWindow = 0.25, kSteadySlip = 0.02, kSteadyChange = 2e-3;
}  // namespace

TEST(AxisymmetricTubeSlow, EffectiveViscosityDecreasesWithFlowRate) {
  const auto wall = tube_wall(kElementSize);
  const double mu_free = cell_free_effective_viscosity(wall);
  const double ratio = tube_velocity_ratio(wall, kN, kM);
  const double dt = 0.5 * time_step_limit(kN);
  const long steps = std::lround(std::ceil(kMaxEnd / dt - 1e-9));
  std::printf("wall %d triangles, cell-free mu_eff = %.5f, tube velocity / <u> = %.4f with the resting cell\n",
              wall->num_triangles(), mu_free, ratio);
  std::vector<TubeRun> runs;
  for (const double U : {0.62, 1.25, 2.52, 5.09, 7.66}) {
    runs.push_back(run_tube(wall, mu_free, ratio, kN, kM, U, dt, steps, kWindow, 100, kSteadySlip, kSteadyChange, true));
    const TubeRun& r = runs.back();
    ASSERT_FALSE(r.blew_up) << r.error;
    EXPECT_TRUE(r.finite);
    EXPECT_LT(r.max_offset, 1e-2) << "the cell should stay on the axis";
    EXPECT_LT(r.max_volume_error, 1e-4);  // constrained
    EXPECT_LT(r.slip, kSteadySlip) << "not steady by t = " << kMaxEnd << " at U = " << U;
    EXPECT_LT(r.mu_rel_change, kSteadyChange) << "mu_eff not steady by t = " << kMaxEnd << " at U = " << U;
  }
  std::printf("  target U  U_tube  mu_eff/mu_0  change over last %.2f  slip      length  radius  t      steps  s\n",
              kWindow);
  for (const TubeRun& r : runs) {
    std::printf("  %.2f      %.3f   %.5f      %.2e              %.2e  %.3f   %.3f   %.3f  %ld   %.0f\n", r.target,
                r.tube_velocity, r.mu_rel, r.mu_rel_change, r.slip, r.length, r.radius, r.time, r.steps, r.seconds);
  }
  for (std::size_t i = 0; i < runs.size(); ++i) {
    EXPECT_GT(runs[i].mu_rel, 1.0);
    if (i == 0) continue;
    const double gap = runs[i - 1].mu_rel - runs[i].mu_rel;
    EXPECT_GT(gap, 0.0) << "mu_eff should decrease from U = " << runs[i - 1].target << " to " << runs[i].target;
    EXPECT_LT(std::max(runs[i - 1].mu_rel_change, runs[i].mu_rel_change), gap)
        << "the transient left is larger than the step in mu_eff between U = " << runs[i - 1].target << " and "
        << runs[i].target;
  }
}
