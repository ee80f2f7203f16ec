#pragma once
// Free-space Stokes kernels of eq. (2), in the convention of docs/references.md:
//   Stokeslet  G_ij(r) = delta_ij / r + r_i r_j / r^3     (u = G f / (8 pi mu)),
//   stresslet  T_ijk(r) = -6 r_i r_j r_k / r^5,
// with r = x - x0, x the source (integration) point and x0 the target. G is even in r and T odd,
// so the sign of r matters only for T: with this sign the double layer of a closed surface
// with outward normal, integral T_ijk(x - x0) n_k(x) dS(x), is -8 pi delta_ij for x0 inside.
// T is symmetric in all three indices, so which index is contracted with which density does
// not matter. Small inline functions for hot loops; none checks for r = 0.
#include <Eigen/Core>
#include <cmath>

namespace rbcflow {

// G(r) as a matrix.
inline Eigen::Matrix3d stokeslet(const Eigen::Vector3d& r) {
  const double r2 = r.squaredNorm(), inv_r = 1.0 / std::sqrt(r2);
  return inv_r * Eigen::Matrix3d::Identity() + (inv_r * inv_r * inv_r) * r * r.transpose();
}

// G(r) f = f / r + r (r . f) / r^3.
inline Eigen::Vector3d stokeslet_apply(const Eigen::Vector3d& r, const Eigen::Vector3d& f) {
  const double r2 = r.squaredNorm(), inv_r = 1.0 / std::sqrt(r2);
  return inv_r * f + (inv_r * inv_r * inv_r * r.dot(f)) * r;
}

// One component T_ijk(r).
inline double stresslet(const Eigen::Vector3d& r, int i, int j, int k) {
  const double r2 = r.squaredNorm();
  return -6.0 * r[i] * r[j] * r[k] / (r2 * r2 * std::sqrt(r2));
}

// sum_jk T_ijk(r) q_j n_k = -6 r_i (r . q)(r . n) / r^5.
inline Eigen::Vector3d stresslet_apply(const Eigen::Vector3d& r, const Eigen::Vector3d& q,
                                       const Eigen::Vector3d& n) {
  const double r2 = r.squaredNorm();
  return (-6.0 * r.dot(q) * r.dot(n) / (r2 * r2 * std::sqrt(r2))) * r;
}

}  // namespace rbcflow
