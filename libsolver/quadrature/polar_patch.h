#pragma once
// The floating partition of unity of section 5.4: the mask eta of eq. (31) and the polar
// quadrature of I_1 (eq. 33) on a patch of the reference sphere centred on a target.
#include <Eigen/Core>
#include <vector>

#include "geometry/sph/gauss_legendre.h"

namespace rbcflow {

// eta(rho) = exp(2 e^{-1/t} / (t - 1)), t = rho / rho_1 < 1; 0 beyond (eq. 31).
double patch_mask(double rho, double rho1);

struct PatchPoint {
  double theta, phi;  // parameters of the point on the reference sphere
  double rho;         // great-circle distance to the centre
  double weight;      // eta(rho) sin(rho) w_rho w_varphi: integral = sum f(point) weight
};

// Radial rule: Gauss-Legendre in rho on [0, rho_1], or, for a target at parametric distance
// delta > 0 off the surface, Gauss-Legendre after the sinh map rho = delta sinh(mu (s + 1) / 2),
// mu = asinh(rho_1 / delta), which clusters points near the centre (Johnston & Elliott 2005).
std::vector<PatchPoint> polar_patch(double theta0, double phi0, double rho1, int n_rho, int n_varphi,
                                    double delta = 0.0);
// The same with the n_rho-point Gauss-Legendre rule given (callers building many patches).
std::vector<PatchPoint> polar_patch(double theta0, double phi0, double rho1, const GaussLegendreRule& radial,
                                    int n_varphi, double delta = 0.0);

}  // namespace rbcflow
