#pragma once
// Hasimoto's Ewald split of the Stokeslet and stresslet (paper eq. 24-28, written as in
// docs/references.md section 2 with the splitting parameter xi; the paper's alpha = pi / xi^2):
//   G^per(r) = sum_p S^R(r + p L) + (1/V) sum_{k != 0} S^F(k) e^{i k.r},
//   T^per(r) = sum_p T^R(r + p L) + (1/V) sum_{k != 0} T^F(k) e^{i k.r},
// k = 2 pi (n1/L1, n2/L2, n3/L3), r = x - x0 (source minus target, as in stokes_kernels.h).
// Both Fourier parts carry the same screening H(k) = (1 + k^2/(4 xi^2)) exp(-k^2/(4 xi^2)),
// so one scalar ewald_fourier_scale(k^2) = 8 pi H(k) / k^2 serves both. Inline, for hot loops.
#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace rbcflow {

// S^R(r) = a(r) I + b(r) r r^T / r^2 (eq. 24):
//   a = erfc(xi r)/r - (2 xi/sqrt(pi)) e^{-xi^2 r^2},  b = erfc(xi r)/r + (2 xi/sqrt(pi)) e^{-xi^2
//   r^2}.
struct StokesletSplitCoeffs {
  double a, b;
};
inline StokesletSplitCoeffs ewald_real_stokeslet_coeffs(double r, double xi) {
  const double e = std::erfc(xi * r) / r;
  const double g = 2.0 * xi * std::numbers::inv_sqrtpi * std::exp(-xi * xi * r * r);
  return {e - g, e + g};
}

inline Eigen::Matrix3d ewald_real_stokeslet(const Eigen::Vector3d& r, double xi) {
  const double rn = r.norm();
  const StokesletSplitCoeffs c = ewald_real_stokeslet_coeffs(rn, xi);
  return c.a * Eigen::Matrix3d::Identity() + (c.b / (rn * rn)) * r * r.transpose();
}

// S^R(r) f.
inline Eigen::Vector3d ewald_real_stokeslet_apply(const Eigen::Vector3d& r, double xi,
                                                  const Eigen::Vector3d& f) {
  const double r2 = r.squaredNorm();
  const StokesletSplitCoeffs c = ewald_real_stokeslet_coeffs(std::sqrt(r2), xi);
  return c.a * f + (c.b * r.dot(f) / r2) * r;
}

// lim_{r -> 0} (S^R(r) - G(r)) = -(4 xi / sqrt(pi)) I: the regular part of S^R at its own
// source, which the real-space sums leave out with the r = 0 pair.
inline double ewald_real_stokeslet_self(double xi) { return -4.0 * xi * std::numbers::inv_sqrtpi; }

// T^R_ijk(r) = alpha(r) r_i r_j r_k + beta(r) (delta_ij r_k + delta_jk r_i + delta_ki r_j) (eq.
// 27):
//   alpha = -6 erfc(xi r)/r^5 - [12 xi/(sqrt(pi) r^4) + 8 xi^3/(sqrt(pi) r^2)] e^{-xi^2 r^2},
//   beta  = (4 xi^3 / sqrt(pi)) e^{-xi^2 r^2}.
struct StressletSplitCoeffs {
  double alpha, beta;
};
inline StressletSplitCoeffs ewald_real_stresslet_coeffs(double r, double xi) {
  const double r2 = r * r, xi2 = xi * xi;
  const double e = xi * std::numbers::inv_sqrtpi * std::exp(-xi2 * r2);
  const double alpha =
      -6.0 * std::erfc(xi * r) / (r2 * r2 * r) - (12.0 / (r2 * r2) + 8.0 * xi2 / r2) * e;
  return {alpha, 4.0 * xi2 * e};
}

// sum_jk T^R_ijk(r) q_j n_k = alpha r_i (r.q)(r.n) + beta (q_i (r.n) + n_i (r.q) + r_i (q.n)).
inline Eigen::Vector3d ewald_real_stresslet_apply(const Eigen::Vector3d& r, double xi,
                                                  const Eigen::Vector3d& q,
                                                  const Eigen::Vector3d& n) {
  const StressletSplitCoeffs c = ewald_real_stresslet_coeffs(r.norm(), xi);
  const double rq = r.dot(q), rn = r.dot(n);
  return (c.alpha * rq * rn + c.beta * q.dot(n)) * r + c.beta * (rn * q + rq * n);
}

// 8 pi H(k) / k^2 = 8 pi (1/k^2 + 1/(4 xi^2)) exp(-k^2/(4 xi^2)), k2 = |k|^2 > 0 (eq. 25, 28).
inline double ewald_fourier_scale(double k2, double xi) {
  const double c = 0.25 / (xi * xi);
  return 8.0 * std::numbers::pi * (1.0 / k2 + c) * std::exp(-c * k2);
}

// S^F(k) f = scale (f - k (k.f)/k^2).
inline Eigen::Vector3d ewald_fourier_stokeslet_apply(const Eigen::Vector3d& k, double xi,
                                                     const Eigen::Vector3d& f) {
  const double k2 = k.squaredNorm();
  return ewald_fourier_scale(k2, xi) * (f - (k.dot(f) / k2) * k);
}

// T^F(k) contracted with q_j n_k is purely imaginary: the function returns v with
// sum_jk T^F_ijk q_j n_k = i v_i,
//   v = scale [n (k.q) + q (k.n) + k (q.n) - 2 k (k.q)(k.n)/k^2].
inline Eigen::Vector3d ewald_fourier_stresslet_apply(const Eigen::Vector3d& k, double xi,
                                                     const Eigen::Vector3d& q,
                                                     const Eigen::Vector3d& n) {
  const double k2 = k.squaredNorm(), kq = k.dot(q), kn = k.dot(n);
  return ewald_fourier_scale(k2, xi) * (kq * n + kn * q + (q.dot(n) - 2.0 * kq * kn / k2) * k);
}

}  // namespace rbcflow
