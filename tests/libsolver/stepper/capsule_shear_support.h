#pragma once
// A spherical neo-Hookean capsule (radius 1, no bending) in the free-space simple shear
// u = (gamma z, 0, 0), lambda = 1 (docs/references.md section 5), shared by the fast and the slow
// shear validations. Units: mu = 1, gamma = 1, so G_s = 1 / Ca_G.
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>

#include "geometry/surface/inertia_ellipsoid.h"
#include "geometry/surface/reference_shapes.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow::shear_test {

struct ShearRun {
  double ca = 0;                   // Ca_G
  double dt = 0;
  double deformation = 0;          // Taylor D of the inertia ellipsoid at the end
  double inclination = 0;          // long axis from the flow direction x towards +z (rad)
  double deformation_change = 0;   // |D(t_end) - D(t_end - one relaxation time)|
  double inclination_change = 0;
  double volume_error = 0;         // |V / V0 - 1| at the end (no constraint)
  int steps = 0;
};

// Small-deformation rate of the slow l = 2 spheroidal mode of a neo-Hookean sphere
// (K_s = 3 G_s), lambda = 1, in units of G_s / (mu a): docs/references.md section 4.
inline double slow_l2_rate() {
  const double l = 2, L = 6, lam = 1, Gs = 1, Ks = 3;
  const double Rrr = (2 * l * l + 3 * l + 4) / (l + 1) + lam * (2 * l * l + l + 3) / l;
  const double Rrp = -3 * (l + lam * (l + 1)), Rpp = (2 * l + 1) * (1 + lam);
  const double Krr = 4 * Ks, Kpp = Ks * L + Gs * (L - 2);
  const double a = L * Rrr * Rpp - Rrp * Rrp, b = -L * (Krr * Rpp + Kpp * Rrr) - 4 * Ks * L * Rrp;
  const double c = L * Krr * Kpp - 4 * Ks * Ks * L * L;
  return (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);  // 0.2484
}

// dt from the limit (37) with the neo-Hookean area modulus K_s = 3 G_s in place of E_D and
// h_eff = sqrt(4 pi) / N, times `safety`.
inline double stable_dt(double ca, int order, double safety) {
  const double h = std::sqrt(4 * std::numbers::pi) / order;
  return safety * 2.5 * std::pow(h, 1.2) / (3.0 / ca);
}

inline void measure(const CellStepper& s, double& D, double& theta) {
  const InertiaEllipsoid e = inertia_ellipsoid(s.cells()[0].shape.geometry(*s.grids().n_grid));
  D = e.taylor_deformation();
  const Eigen::Vector3d axis = e.axes.col(2);
  theta = std::atan(axis.z() / axis.x());  // in (-pi/2, pi/2): the sign of the axis does not matter
}

// Runs for `relaxation_times` times 1 / (w_slow G_s) (the slow l = 2 mode: the approach to the
// steady shape), printing D and theta every `print_every` relaxation times.
inline ShearRun run_shear(double ca, int order, int dealias_order, double safety, double relaxation_times,
                          double print_every = 1.0, TimeScheme scheme = TimeScheme::euler) {
  const double G = 1.0 / ca, gamma = 1.0;
  auto grids = CellGrids::make(order, dealias_order);
  Cell cell;
  cell.shape = make_sphere(order);
  cell.membrane = std::make_shared<const Membrane>(make_sphere(order), grids,
                                                   MembraneParameters{std::make_shared<NeoHookeanLaw>(G), 0.0});
  CellStepperOptions o;
  o.dt = stable_dt(ca, order, safety);
  o.scheme = scheme;
  o.viscosity_ratio = 1.0;
  o.background = [gamma](const Eigen::Vector3d& x) { return Eigen::Vector3d(gamma * x.z(), 0, 0); };
  CellStepper stepper({cell}, grids, o);

  const double t_relax = 1.0 / (slow_l2_rate() * G);
  const int steps_per_relax = static_cast<int>(std::ceil(t_relax / o.dt));
  const int total = static_cast<int>(std::ceil(relaxation_times * steps_per_relax));
  const int print_steps = std::max(1, static_cast<int>(print_every * steps_per_relax));
  ShearRun r;
  r.ca = ca;
  r.dt = o.dt;
  double D_prev = 0, th_prev = 0;
  std::printf("  Ca_G = %.4f  N = %d  M = %d  %s  dt = %.3e  t_relax = %.4f  (%d steps)\n", ca, order, dealias_order,
              scheme == TimeScheme::euler ? "Euler" : "AB2", o.dt, t_relax, total);
  for (int n = 1; n <= total; ++n) {
    const StepReport rep = stepper.step();
    r.volume_error = rep.max_volume_error;
    if (n == total - steps_per_relax) measure(stepper, D_prev, th_prev);
    if (n % print_steps == 0 || n == total) {
      double D, th;
      measure(stepper, D, th);
      std::printf("    t = %7.4f  D = %.6f  theta/pi = %.5f  dV = %.1e\n", stepper.time(), D, th / std::numbers::pi,
                  rep.max_volume_error);
      std::fflush(stdout);
    }
  }
  measure(stepper, r.deformation, r.inclination);
  r.deformation_change = std::abs(r.deformation - D_prev);
  r.inclination_change = std::abs(r.inclination - th_prev);
  r.steps = total;
  return r;
}

// Barthes-Biesel & Rallison (1981), docs/references.md section 5, nu_s = 1/2 (neo-Hookean):
// D = 25/12 Ca_G and theta = pi/4 - Ca_G [(79 + 43 nu + 16 nu^2) lambda + 96 + 72 nu + 24 nu^2]
// / [32 (1 + nu)(2 + nu)].
inline double theory_deformation(double ca) { return 25.0 / 12.0 * ca; }
inline double theory_inclination_slope(double lambda) {
  const double nu = 0.5;
  return ((79 + 43 * nu + 16 * nu * nu) * lambda + 96 + 72 * nu + 24 * nu * nu) / (32 * (1 + nu) * (2 + nu));
}

}  // namespace rbcflow::shear_test
