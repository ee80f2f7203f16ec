// Small-deformation relaxation of a spherical capsule (paper section 9, fig. 4; docs/references.md
// section 4): Hookean law (41) with E_S = 1, E_D = 2.5, no bending. The capsule starts in the
// slow spheroidal eigenmode (l, m = 2) with amplitude 1e-4; its Y_lm coefficient decays as
// exp(-w t) with w_slow from the secular equation. Forward Euler measures
// -ln(1 - w dt) / dt (eq. 43), inverted here before the comparison.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "capsule_relaxation.h"

using namespace rbcflow;
using test::measured_rate;
using test::slow_mode;

TEST(CapsuleRelaxation, SlowModeRatesMatchTheoryLambda1) {
  for (int l : {2, 3}) {
    const double w = measured_rate(l, 1.0, 12, 0.005, 60), th = slow_mode(l, 1.0, 1.0, 3.5).w_slow;
    std::printf("  l = %d lambda = 1: measured %.5f theory %.5f  rel %.1e\n", l, w, th, std::abs(w / th - 1));
    EXPECT_NEAR(w / th, 1.0, 0.01);
  }
}

TEST(CapsuleRelaxation, SlowModeRateMatchesTheoryLambda5) {
  const double w = measured_rate(2, 5.0, 12, 0.005, 40), th = slow_mode(2, 5.0, 1.0, 3.5).w_slow;
  std::printf("  l = 2 lambda = 5: measured %.5f theory %.5f  rel %.1e\n", w, th, std::abs(w / th - 1));
  EXPECT_NEAR(w / th, 1.0, 0.01);
}

// The highest degree each resolution carries (l = N - 2): the singular quadrature's polar patch
// must resolve it. With 2 sqrt(N) radial patch points (the former default) these rates missed
// by 1.1% (N = 12) and 13% (N = 16); with 3 sqrt(N) by 0.29% and 0.43% (the same figures as
// from 500 steps of 1e-3).
TEST(CapsuleRelaxation, HighestResolvedDegreesMatchTheory) {
  for (const auto& [N, l] : {std::pair{12, 10}, std::pair{16, 14}}) {
    const double w = measured_rate(l, 1.0, N, 0.005, 60), th = slow_mode(l, 1.0, 1.0, 3.5).w_slow;
    std::printf("  N = %d l = %d lambda = 1: measured %.5f theory %.5f  rel %.1e\n", N, l, w, th, std::abs(w / th - 1));
    EXPECT_NEAR(w / th, 1.0, 0.01) << "N = " << N << ", l = " << l;
  }
}
