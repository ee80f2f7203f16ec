#pragma once
// Exact integrals of the contact repulsion for the tests of libsolver/stepper/contact_force.h,
// shared by the default tests and the relaxation of two spheres pressed together.
#include <cmath>
#include <functional>
#include <numbers>

#include "geometry/surface/sh_surface.h"
#include "libsolver/stepper/contact_force.h"

namespace rbcflow::test {

// The integral of f over [a, b] by composite Gauss-Legendre (4 points on each of n panels).
inline double integrate(const std::function<double(double)>& f, double a, double b, int n) {
  static const double x[4] = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563, 0.8611363115940526};
  static const double w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461, 0.3478548451374538};
  const double h = (b - a) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) sum += 0.5 * h * w[k] * f(a + h * (i + 0.5 + 0.5 * x[k]));
  return sum;
}

// The force on a rigid unit sphere from another at gap g: the integral over it of t(|x - c_b| -
// 1) along the other's normal (x - c_b) / |x - c_b|, about the line of centres, to 1e-12.
inline double two_sphere_force(const ContactLaw& law, double g) {
  return integrate(
      [&](double theta) {
        const double ax = std::cos(theta) - (2.0 + g), r = std::hypot(ax, std::sin(theta));
        return 2.0 * std::numbers::pi * law.traction(r - 1.0) * ax / r * std::sin(theta);
      },
      0.0, std::numbers::pi, 20000);
}

// The net force of `density` (grid points x 3) over the surface `x` on the grid of `t`.
inline Eigen::Vector3d net_force(const SHCoeffs& x, const SHTransform& t, const Eigen::MatrixXd& density) {
  const SurfaceGeometry g = surface_geometry(x, t);
  return (density.transpose() * g.area_weight);
}

}  // namespace rbcflow::test
