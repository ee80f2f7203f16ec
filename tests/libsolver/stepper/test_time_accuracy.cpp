// Time accuracy of the stepper (paper section 9, fig. 5, eq. 43): the damping rate of a
// relaxing capsule (Hookean law (41), E_S = 1, E_D = 2.5, no bending, lambda = 1, free space,
// slow spheroidal mode l = 2, m = 2, amplitude 1e-4, as in test_capsule_relaxation) measured
// at several dt. The measured rate w(dt) = w_0 + c dt^p: its order p comes from three dt
// halving (Richardson, so the spatial error in w_0 cancels), and its error against the
// extrapolated w_0 is compared with the discrete-time rate of du/dt = -w u:
//   forward Euler  u_{n+1} = (1 - h) u_n,                         dw/w = -ln(1 - h)/h - 1   (43)
//   AB2            u_{n+1} = u_n - h (3 u_n - u_{n-1}) / 2,       dw/w = -ln(z)/h - 1,
//                  z = (1 - 3h/2 + sqrt((1 - 3h/2)^2 + 2h)) / 2 (its principal root), h = w dt.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "capsule_relaxation.h"

using namespace rbcflow;

namespace {

double euler_relative_error(double h) { return -std::log(1 - h) / h - 1; }
double ab2_relative_error(double h) {
  const double b = 1 - 1.5 * h, z = (b + std::sqrt(b * b + 2 * h)) / 2;
  return -std::log(z) / h - 1;
}

constexpr int kL = 2;  // the mode (l, m = 2) of test::relaxing_capsule (E_S = 1, E_D = 2.5)

// Rate of mode (l, m) measured from ln(amplitude) between t_start and t_end (both multiples
// of dt), the capsule started in the theoretical slow eigenmode.
double measured_rate(TimeScheme scheme, int N, double dt, double t_start, double t_end) {
  auto grids = CellGrids::make(N, 2 * N);
  CellStepperOptions o;
  o.dt = dt;
  o.scheme = scheme;
  o.viscosity_ratio = 1.0;
  CellStepper stepper({test::relaxing_capsule(kL, 1.0, N, grids)}, grids, o);
  auto amplitude = [&]() { return test::mode_amplitude(stepper.cells()[0].shape, kL, *grids->n_grid); };
  const long n_start = std::lround(t_start / dt), n_end = std::lround(t_end / dt);
  double a_start = amplitude();
  for (long n = 1; n <= n_end; ++n) {
    stepper.step();
    if (n == n_start) a_start = amplitude();
  }
  return -std::log(amplitude() / a_start) / ((n_end - n_start) * dt);
}

struct Convergence {
  std::vector<double> dt, rate;
  double order = 0, extrapolated = 0;
};

// Rates at dt0, dt0/2, dt0/4; order from the two differences; w_0 by Richardson with that order.
Convergence converge(TimeScheme scheme, int N, double dt0, double t_start, double t_end) {
  Convergence c;
  for (double dt = dt0; c.dt.size() < 3; dt /= 2) {
    c.dt.push_back(dt);
    c.rate.push_back(measured_rate(scheme, N, dt, t_start, t_end));
  }
  c.order = std::log2((c.rate[0] - c.rate[1]) / (c.rate[1] - c.rate[2]));
  const double f = std::pow(2.0, c.order);
  c.extrapolated = (f * c.rate[2] - c.rate[1]) / (f - 1);
  return c;
}

void print(const char* name, const Convergence& c, double (*predicted)(double)) {
  std::printf("  %s: order %.3f, extrapolated w_0 = %.8f\n", name, c.order, c.extrapolated);
  std::printf("    dt        w dt      measured w    dw/w measured  dw/w predicted  ratio\n");
  for (std::size_t i = 0; i < c.dt.size(); ++i) {
    const double h = c.extrapolated * c.dt[i], e = c.rate[i] / c.extrapolated - 1;
    std::printf("    %.2e  %.2e  %.8f    %+.3e     %+.3e      %.3f\n", c.dt[i], h, c.rate[i], e, predicted(h),
                e / predicted(h));
  }
}

}  // namespace

TEST(TimeAccuracy, EulerIsFirstOrderAndFollowsEq43) {
  const Convergence c = converge(TimeScheme::euler, 8, 0.016, 0.25, 1.25);
  print("forward Euler", c, euler_relative_error);
  const double w_theory = test::slow_mode(kL, 1.0, 1.0, 3.5).w_slow;
  std::printf("  theory w_slow = %.8f (extrapolated / theory - 1 = %.1e)\n", w_theory, c.extrapolated / w_theory - 1);
  EXPECT_NEAR(c.order, 1.0, 0.15);
  for (std::size_t i = 0; i < c.dt.size(); ++i) {
    const double h = c.extrapolated * c.dt[i];
    EXPECT_NEAR((c.rate[i] / c.extrapolated - 1) / euler_relative_error(h), 1.0, 0.05) << "dt = " << c.dt[i];
  }
}

TEST(TimeAccuracy, AdamsBashforthIsSecondOrder) {
  const Convergence c = converge(TimeScheme::ab2, 8, 0.016, 0.25, 1.25);
  print("AB2", c, ab2_relative_error);
  EXPECT_NEAR(c.order, 2.0, 0.3);
  for (std::size_t i = 0; i < c.dt.size(); ++i) {
    const double h = c.extrapolated * c.dt[i];
    EXPECT_NEAR((c.rate[i] / c.extrapolated - 1) / ab2_relative_error(h), 1.0, 0.1) << "dt = " << c.dt[i];
  }
}
