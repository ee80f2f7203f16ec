// The full relaxation test of section 9 (fig. 4; issue 7 validation 2, labelled slow): slow-mode
// damping rates for l = 2..10, m = 2, lambda = 1 and 5, N = 12, dt = 1e-3, within 1% of the
// secular equation (REFERENCES.md section 4). The paper reports < 0.2% at this resolution;
// l = 10 is the largest degree N = 12 resolves (its Cartesian components reach degree 11).
// Free space: the theory is for an unbounded fluid (the paper's box of side 20 adds ~(a/L)^3).
// Measured (commit 8e5ceb6, 1 thread beside other jobs, ~25 min), relative error of w_slow:
//   l        2       3       4       5       6       7       8       9       10
//   lam = 1  2.9e-5  1.6e-4  3.3e-4  3.7e-4  5.3e-4  1.4e-3  1.3e-3  9.8e-4  1.06e-2
//   lam = 5  1.4e-5  1.7e-4  3.5e-4  3.6e-4  5.0e-4  1.4e-3  1.3e-3  9.1e-4  1.09e-2
// so the test FAILS at l = 10, the mode at the resolution limit (the paper reports < 0.2% for
// every l at N = 12); with the patch points evaluated from the expansions
// (spectral_interpolation) l = 10, lambda = 1 is -8.3e-3, with a Hermite grid refined 4x
// -8.4e-3: interpolation is not the cause. The polar patch's radial rule is: l = 10 with
// radial x angular patch points (default 8 x 16) 16 x 32: -2.0e-3; 12 x 24: -2.1e-3;
// 16 x 16: -1.6e-3; 12 x 12: -1.0e-3 (lambda = 5: -1.0e-3), at about the default's cost
// (144 against 128 points); l = 8 with 12 x 12: -1.9e-3 (default 1.3e-3); a patch 1.5x larger
// at the default points: +3.6e-2 (session 5, /tmp driver, 500 steps each). A default of
// 12 x 12 at N = 12 is the next step; it needs the whole sweep and suite re-run. Left failing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "capsule_relaxation.h"

using namespace rbcflow;

TEST(CapsuleRelaxationSlow, SlowModeRatesForDegrees2To10) {
  for (double lambda : {1.0, 5.0}) {
    for (int l = 2; l <= 10; ++l) {
      const double th = test::slow_mode(l, lambda, 1.0, 3.5).w_slow;
      // The capsule starts in the slow eigenmode, so any window measures w_slow: t = 0.5 (the
      // amplitude falls 2-12%, against rounding of ~1e-10 of its 1e-4), as the default suite's
      // t = 0.3 which reaches 3e-5. (A fall by e^-1 would need 4,000-20,000 steps per mode: w_slow
      // decreases with l without bending.)
      const int steps = 500;
      const double w = test::measured_rate(l, lambda, 12, 1e-3, steps);
      std::printf("  l = %2d lambda = %.0f: measured %.5f theory %.5f  rel %.1e (%d steps)\n", l, lambda, w, th,
                  std::abs(w / th - 1), steps);
      EXPECT_NEAR(w / th, 1.0, 0.01) << "l = " << l << ", lambda = " << lambda;
    }
  }
}
