#pragma once
// Small-deformation relaxation of a spherical capsule (paper section 9, fig. 4; docs/references.md
// section 4), shared by the default and the slow relaxation tests: Hookean law (41) with
// E_S = 1, E_D = 2.5, no bending. The capsule starts in the slow spheroidal eigenmode (l, m = 2)
// with amplitude 1e-4; its Y_lm coefficient decays as exp(-w t) with w_slow from the secular
// equation. Forward Euler measures -ln(1 - w dt) / dt (eq. 43), inverted before comparing.
#include <cmath>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow::test {


struct Theory {
  double w_slow, b_over_a;  // rate and poloidal/radial amplitude ratio of the slow mode
};

inline Theory slow_mode(int l, double lam, double Gs, double Ks) {
  const double L = l * (l + 1.0);
  const double Rrr = (2.0 * l * l + 3 * l + 4) / (l + 1) + lam * (2.0 * l * l + l + 3) / l;
  const double Rrp = -3 * (l + lam * (l + 1));
  const double Rpp = (2 * l + 1) * (1 + lam);
  const double Krr = 4 * Ks, Kpp = Ks * L + Gs * (L - 2);
  // (Krr - w Rrr) L (Kpp - w Rpp) - (2 Ks L + w Rrp)^2 = 0: a w^2 + b w + c = 0.
  const double a = L * Rrr * Rpp - Rrp * Rrp;
  const double b = -L * (Krr * Rpp + Kpp * Rrr) - 4 * Ks * L * Rrp;
  const double c = L * Krr * Kpp - 4 * Ks * Ks * L * L;
  const double w = (-b - std::sqrt(b * b - 4 * a * c)) / (2 * a);
  return {w, (Krr - w * Rrr) / (2 * Ks * L + w * Rrp)};
}

// The unit sphere started in the slow eigenmode (l, 2) of viscosity ratio lam,
// x = u + eps (Y u + (B/A) grad_s Y), with the Hookean membrane (E_S = 1, E_D = 2.5) whose
// reference is the unit sphere.
inline Cell relaxing_capsule(int l, double lam, int N, const std::shared_ptr<const CellGrids>& grids,
                             double eps = 1e-4) {
  const Theory th = slow_mode(l, lam, 1.0, 3.5);
  const SHTransform sample(2 * N, SphGrid::gauss(2 * N), 1);
  SHCoeffs y(2 * N, 1);
  y.a(l, 2) = 1.0;
  const Eigen::MatrixXd Y = sample.synthesize(y), Yt = sample.synthesize(y, 1, 0), Yp = sample.synthesize(y, 0, 1);
  Eigen::MatrixXd x(sample.grid().size(), 3);
  for (int p = 0; p < sample.grid().size(); ++p) {
    const double t = sample.grid().theta()[p / sample.grid().n_phi()], ph = sample.grid().phi(p % sample.grid().n_phi());
    const Eigen::Vector3d u(std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph), std::cos(t));
    const Eigen::Vector3d et(std::cos(t) * std::cos(ph), std::cos(t) * std::sin(ph), -std::sin(t)), ep(-std::sin(ph), std::cos(ph), 0);
    const Eigen::Vector3d grad = Yt(p, 0) * et + Yp(p, 0) / std::sin(t) * ep;
    x.row(p) = u + eps * (Y(p, 0) * u + th.b_over_a * grad);
  }
  Cell cell;
  cell.shape = SHSurface(sample.analyze(x, N));
  cell.membrane = std::make_shared<const Membrane>(make_sphere(N), grids,
                                                   MembraneParameters{std::make_shared<HookeanLaw>(1.0, 2.5), 0.0});
  return cell;
}

// Radial amplitude of Y_l2 on a near-unit sphere: integral (x . u - 1) Y dOmega / integral Y^2 dOmega.
inline double mode_amplitude(const SHSurface& s, int l, const SHTransform& tn) {
  const int N = s.coeffs().order();
  SHCoeffs yn(N, 1);
  yn.a(l, 2) = 1.0;
  const Eigen::MatrixXd Yn = tn.synthesize(yn), U = tn.synthesize(make_sphere(N).coeffs());
  const Eigen::MatrixXd xs = tn.synthesize(s.coeffs());
  double num = 0, den = 0;
  for (int p = 0; p < tn.grid().size(); ++p) {
    const double w = tn.grid().sphere_weight(p);
    num += w * (xs.row(p).dot(U.row(p)) - 1.0) * Yn(p, 0);
    den += w * Yn(p, 0) * Yn(p, 0);
  }
  return num / den;
}

// Measured decay rate of mode (l, 2) over `steps` forward-Euler steps of dt, eq. (43) inverted.
inline double measured_rate(int l, double lam, int N, double dt, int steps) {
  auto grids = CellGrids::make(N, 2 * N);
  CellStepperOptions o;
  o.dt = dt;
  o.viscosity_ratio = lam;
  o.gmres_tolerance = 1e-10;
  CellStepper stepper({relaxing_capsule(l, lam, N, grids)}, grids, o);
  const double a0 = mode_amplitude(stepper.cells()[0].shape, l, *grids->n_grid);
  for (int s = 0; s < steps; ++s) stepper.step();
  const double measured = -std::log(mode_amplitude(stepper.cells()[0].shape, l, *grids->n_grid) / a0) / (steps * dt);
  return (1.0 - std::exp(-measured * dt)) / dt;  // invert eq. (43)
}

}  // namespace rbcflow::test
