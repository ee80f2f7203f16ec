// The full relaxation test of section 9 (fig. 4; issue 7 validation 2, labelled slow): slow-mode
// damping rates for l = 2..10, m = 2, lambda = 1 and 5, N = 12, dt = 1e-3, within 1% of the
// secular equation (docs/references.md section 4). The paper reports < 0.2% at this resolution;
// l = 10 is the largest degree N = 12 resolves (its Cartesian components reach degree 11).
// Free space: the theory is for an unbounded fluid (the paper's box of side 20 adds ~(a/L)^3).
// Measured with the patch rule of 3 sqrt(N) radial points (11 x 22 at N = 12; 1 thread beside
// another run, 778 s), relative error of w_slow:
//   l        2       3       4       5       6       7       8       9       10
//   lam = 1  7.3e-5  1.2e-4  1.9e-4  3.4e-4  4.9e-4  1.0e-3  1.6e-3  2.4e-3  2.9e-3
//   lam = 5  7.5e-5  1.2e-4  1.9e-4  3.4e-4  4.9e-4  1.1e-3  1.7e-3  2.4e-3  2.8e-3
// With the former rule of 2 sqrt(N) (8 x 16 at N = 12) l = 10 missed by 1.06e-2 (lambda = 1)
// and 1.09e-2 (lambda = 5), the other degrees as now. The polar patch's radial rule was the
// cause (not the Hermite interpolation: spectral patch values -8.3e-3, a 4x finer Hermite grid
// -8.4e-3): l = 10, lambda = 1 with radial x angular points 8 x 16 -1.06e-2; 9 x 18 -9.0e-4;
// 10 x 20 -2.7e-3; 12 x 16 -2.2e-3; 12 x 24 -2.1e-3; 16 x 32 -2.0e-3. At N = 16 the l = 14
// mode missed by 13% with 8 x 16 and by 0.42-0.49% with 12 x 16, 12 x 24 or 16 x 32.
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
