#include "polar_patch.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "libsolver/quadrature/batch_math.h"

namespace rbcflow {

double patch_mask(double rho, double rho1) {
  const double t = rho / rho1;
  if (t <= 0.0) return 1.0;
  if (t >= 1.0) return 0.0;
  return std::exp(2.0 * std::exp(-1.0 / t) / (t - 1.0));
}

std::vector<PatchPoint> polar_patch(double theta0, double phi0, double rho1, int n_rho, int n_varphi,
                                    double delta) {
  if (n_rho < 1) throw std::invalid_argument("polar_patch: bad radius, point counts or distance");
  return polar_patch(theta0, phi0, rho1, gauss_legendre(n_rho), n_varphi, delta);
}

std::vector<PatchPoint> polar_patch(double theta0, double phi0, double rho1, const GaussLegendreRule& g,
                                    int n_varphi, double delta) {
  const int n_rho = static_cast<int>(g.theta.size());
  if (rho1 <= 0 || rho1 > std::numbers::pi || n_rho < 1 || n_varphi < 1 || delta < 0) {
    throw std::invalid_argument("polar_patch: bad radius, point counts or distance");
  }
  // Orthonormal frame (e1, e2, u0) at the centre, e1 = e_phi: defined at the poles too, and a
  // rotation about the axis carries the patch of (theta0, phi0) onto that of (theta0, phi0 + a)
  // point by point (the corrections of a ring of grid nodes share one patch, shifted in phi).
  const Eigen::Vector3d u0(std::sin(theta0) * std::cos(phi0), std::sin(theta0) * std::sin(phi0), std::cos(theta0));
  const Eigen::Vector3d e1(-std::sin(phi0), std::cos(phi0), 0.0), e2 = u0.cross(e1);

  std::vector<double> rho(n_rho), w_rho(n_rho), cos_rho(n_rho), sin_rho(n_rho);
  const double mu = delta > 0 ? std::asinh(rho1 / delta) : 0.0;
  for (int a = 0; a < n_rho; ++a) {
    // Gauss nodes on [-1, 1] are x = cos(theta): ascending theta gives descending x.
    const double s = std::cos(g.theta[a]);
    if (delta > 0) {
      const double arg = 0.5 * mu * (s + 1.0);
      rho[a] = delta * std::sinh(arg);
      w_rho[a] = g.weights[a] * delta * std::cosh(arg) * 0.5 * mu;
    } else {
      rho[a] = 0.5 * rho1 * (s + 1.0);
      w_rho[a] = 0.5 * rho1 * g.weights[a];
    }
    cos_rho[a] = std::cos(rho[a]);
    sin_rho[a] = std::sin(rho[a]);
    // The radial factor of the weight: the mask eta (eq. 31) times the sphere's area element.
    w_rho[a] *= patch_mask(rho[a], rho1) * sin_rho[a];
  }
  // The points' directions u, then their parameters theta = acos(u_z), phi = atan2(u_y, u_x)
  // a whole patch at a time (batch_math.h).
  const std::size_t n = static_cast<std::size_t>(n_rho) * n_varphi;
  Eigen::Matrix<double, Eigen::Dynamic, 3> u(n, 3);
  const double w_varphi = 2.0 * std::numbers::pi / n_varphi;
  for (int b = 0; b < n_varphi; ++b) {
    const double varphi = w_varphi * (b + 0.5);
    const Eigen::Vector3d dir = std::cos(varphi) * e1 + std::sin(varphi) * e2;
    for (int a = 0; a < n_rho; ++a) u.row(b * n_rho + a) = cos_rho[a] * u0 + sin_rho[a] * dir;
  }
  std::vector<double> theta(n), phi(n);
  batch_atan2(u.col(1).data(), u.col(0).data(), phi.data(), n);
  batch_acos(u.col(2).data(), theta.data(), n);
  std::vector<PatchPoint> points(n);
  for (std::size_t q = 0; q < n; ++q) {
    const int a = static_cast<int>(q % n_rho);
    points[q] = {theta[q], phi[q] < 0 ? phi[q] + 2 * std::numbers::pi : phi[q], rho[a], w_rho[a] * w_varphi};
  }
  return points;
}

}  // namespace rbcflow
