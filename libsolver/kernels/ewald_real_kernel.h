#pragma once
// The real-space kernels S^R and T^R of ewald_kernels.h for one fixed xi, evaluated about twice
// as fast for loops that take one pair at a time (the wall's assembled real space, the patch
// kernels of the corrections; the real-space sums take theirs in packets, ewald_real_batch.h):
// erfc(x) = exp(-x^2) erfcx(x), the scaled complementary error
// function erfcx tabulated once as piecewise Chebyshev interpolants on [0, 8] (erfc to 1.2e-14
// relative; std::erfc beyond), so a pair costs one sqrt, one exp and a short polynomial instead of
// erfc and exp. Values agree with ewald_kernels.h to ~1e-14 relative.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

#include "ewald_kernels.h"

namespace rbcflow {

class EwaldRealKernel {
 public:
  explicit EwaldRealKernel(double xi);

  double xi() const { return xi_; }

  // erfc(x) and exp(-x^2) for x >= 0.
  void erfc_and_gaussian(double x, double& erfc_x, double& gaussian) const {
    gaussian = std::exp(-x * x);
    if (x >= kTableEnd) {
      erfc_x = std::erfc(x);
      return;
    }
    const double s = x * kIntervalsPerUnit;
    const int i = static_cast<int>(s);
    const double t = 2.0 * (s - i) - 1.0;  // local coordinate in [-1, 1]
    const double* c = coefficients_ + static_cast<std::size_t>(i) * kTerms;
    double p = c[kTerms - 1];
    for (int k = kTerms - 2; k >= 0; --k) p = p * t + c[k];
    erfc_x = gaussian * p;
  }

  StokesletSplitCoeffs stokeslet_coeffs(double r) const {
    double e, g;
    erfc_and_gaussian(xi_ * r, e, g);
    const double erfc_over_r = e / r, gauss = two_xi_over_sqrt_pi_ * g;
    return {erfc_over_r - gauss, erfc_over_r + gauss};
  }

  // S^R(r) f, with a single division.
  Eigen::Vector3d stokeslet_apply(const Eigen::Vector3d& r, const Eigen::Vector3d& f) const {
    const double r2 = r.squaredNorm(), rn = std::sqrt(r2), inv_r = 1.0 / rn;
    double e, g;
    erfc_and_gaussian(xi_ * rn, e, g);
    const double erfc_over_r = e * inv_r, gauss = two_xi_over_sqrt_pi_ * g;
    return (erfc_over_r - gauss) * f + ((erfc_over_r + gauss) * inv_r * inv_r * r.dot(f)) * r;
  }

  // S^R(r) as a matrix, for operators assembled once (wall/wall_real_space.h).
  Eigen::Matrix3d stokeslet_matrix(const Eigen::Vector3d& r) const {
    const double r2 = r.squaredNorm(), rn = std::sqrt(r2), inv_r = 1.0 / rn;
    double e, g;
    erfc_and_gaussian(xi_ * rn, e, g);
    const double erfc_over_r = e * inv_r, gauss = two_xi_over_sqrt_pi_ * g;
    return (erfc_over_r - gauss) * Eigen::Matrix3d::Identity() + ((erfc_over_r + gauss) * inv_r * inv_r) * (r * r.transpose());
  }

  StressletSplitCoeffs stresslet_coeffs(double r) const {
    double e, g;
    erfc_and_gaussian(xi_ * r, e, g);
    const double inv_r = 1.0 / r, inv_r2 = inv_r * inv_r, xi2 = xi_ * xi_;
    const double h = 0.5 * two_xi_over_sqrt_pi_ * g;  // xi e^{-xi^2 r^2} / sqrt(pi)
    return {-6.0 * e * inv_r * inv_r2 * inv_r2 - (12.0 * inv_r2 + 8.0 * xi2) * inv_r2 * h,
            4.0 * xi2 * h};
  }

  // sum_jk T^R_ijk(r) q_j n_k.
  Eigen::Vector3d stresslet_apply(const Eigen::Vector3d& r, const Eigen::Vector3d& q,
                                  const Eigen::Vector3d& n) const {
    const StressletSplitCoeffs c = stresslet_coeffs(r.norm());
    const double rq = r.dot(q), rn = r.dot(n);
    return (c.alpha * rq * rn + c.beta * q.dot(n)) * r + c.beta * (rn * q + rq * n);
  }

 private:
  static constexpr double kTableEnd = 8.0;
  static constexpr int kIntervalsPerUnit = 8;
  static constexpr int kTerms = 10;  // polynomial degree 9 in the local coordinate

  double xi_, two_xi_over_sqrt_pi_;
  // Monomial coefficients in t of erfcx on each interval [i, i + 1] / kIntervalsPerUnit: one
  // table for every xi, built once.
  const double* coefficients_;
};

}  // namespace rbcflow
