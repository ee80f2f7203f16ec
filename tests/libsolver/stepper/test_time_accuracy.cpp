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

#include "geometry/reference_shapes.h"
#include "libsolver/stepper/cell_stepper.h"

using namespace rbcflow;

namespace {

struct Mode {
  double w_slow, b_over_a;
};

// REFERENCES.md section 4: the slow root of the secular equation and its B/A ratio.
Mode slow_mode(int l, double lam, double Gs, double Ks) {
  const double L = l * (l + 1.0);
  const double Rrr = (2.0 * l * l + 3 * l + 4) / (l + 1) + lam * (2.0 * l * l + l + 3) / l;
  const double Rrp = -3 * (l + lam * (l + 1));
  const double Rpp = (2 * l + 1) * (1 + lam);
  const double Krr = 4 * Ks, Kpp = Ks * L + Gs * (L - 2);
  const double a = L * Rrr * Rpp - Rrp * Rrp;
  const double b = -L * (Krr * Rpp + Kpp * Rrr) - 4 * Ks * L * Rrp;
  const double c = L * Krr * Kpp - 4 * Ks * Ks * L * L;
  const double w = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  return {w, (Krr - w * Rrr) / (2 * Ks * L + w * Rrp)};
}

double euler_relative_error(double h) { return -std::log(1 - h) / h - 1; }
double ab2_relative_error(double h) {
  const double b = 1 - 1.5 * h, z = (b + std::sqrt(b * b + 2 * h)) / 2;
  return -std::log(z) / h - 1;
}

constexpr int kL = 2, kM = 2;
constexpr double kShear = 1.0, kDilatation = 2.5;

// Rate of mode (l, m) measured from ln(amplitude) between t_start and t_end (both multiples
// of dt), the capsule started in the theoretical slow eigenmode.
double measured_rate(TimeScheme scheme, int N, double dt, double t_start, double t_end) {
  auto grids = CellGrids::make(N, 2 * N);
  const Mode th = slow_mode(kL, 1.0, kShear, kShear + kDilatation);
  const SHTransform sample(2 * N, SphGrid::gauss(2 * N), 1);
  SHCoeffs y(2 * N, 1);
  y.a(kL, kM) = 1.0;
  const Eigen::MatrixXd Y = sample.synthesize(y), Yt = sample.synthesize(y, 1, 0), Yp = sample.synthesize(y, 0, 1);
  Eigen::MatrixXd x(sample.grid().size(), 3);
  const double eps = 1e-4;
  for (int p = 0; p < sample.grid().size(); ++p) {
    const double t = sample.grid().theta()[p / sample.grid().n_phi()], ph = sample.grid().phi(p % sample.grid().n_phi());
    const Eigen::Vector3d u(std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph), std::cos(t));
    const Eigen::Vector3d et(std::cos(t) * std::cos(ph), std::cos(t) * std::sin(ph), -std::sin(t)), ep(-std::sin(ph), std::cos(ph), 0);
    const Eigen::Vector3d grad = Yt(p, 0) * et + Yp(p, 0) / std::sin(t) * ep;
    x.row(p) = u + eps * (Y(p, 0) * u + th.b_over_a * grad);
  }
  Cell cell;
  cell.shape = SHSurface(sample.analyze(x, N));
  cell.membrane = std::make_shared<const Membrane>(
      make_sphere(N), grids, MembraneParameters{std::make_shared<HookeanLaw>(kShear, kDilatation), 0.0});
  CellStepperOptions o;
  o.dt = dt;
  o.scheme = scheme;
  o.viscosity_ratio = 1.0;
  CellStepper stepper({cell}, grids, o);
  const SHTransform& tn = *grids->n_grid;
  SHCoeffs yn(N, 1);
  yn.a(kL, kM) = 1.0;
  const Eigen::MatrixXd Yn = tn.synthesize(yn), U = tn.synthesize(make_sphere(N).coeffs());
  auto amplitude = [&]() {
    const Eigen::MatrixXd xs = tn.synthesize(stepper.cells()[0].shape.coeffs());
    double num = 0, den = 0;
    for (int p = 0; p < tn.grid().size(); ++p) {
      const double w = tn.grid().sphere_weight(p);
      num += w * (xs.row(p).dot(U.row(p)) - 1.0) * Yn(p, 0);
      den += w * Yn(p, 0) * Yn(p, 0);
    }
    return num / den;
  };
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
  const double w_theory = slow_mode(kL, 1.0, kShear, kShear + kDilatation).w_slow;
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
