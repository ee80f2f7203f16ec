#pragma once
// The kernel of a boundary-integral layer as a 3x3 matrix acting on the density:
//   single layer (4):  K(r) = G(r) (free space) or S^R(r) (Ewald real-space part, eq. 24)
//   double layer (5):  K(r)_ij = sum_k T_ijk(r) m_k, m the area-weighted normal
//                      (free space or Ewald real-space T^R, eq. 27),
// with r = x - x0 (source minus target). Both matrices are symmetric. xi = 0 selects the
// free-space kernels; xi > 0 the real-space part of Hasimoto's split with that xi.
#include <Eigen/Core>

#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/kernels/stokes_kernels.h"

namespace rbcflow {

enum class Layer { single, double_ };

struct LayerKernel {
  Layer layer = Layer::single;
  double ewald_xi = 0.0;

  // K(r) for a source of area-weighted normal m (unused by the single layer).
  Eigen::Matrix3d matrix(const Eigen::Vector3d& r, const Eigen::Vector3d& m) const {
    if (layer == Layer::single) return ewald_xi > 0 ? ewald_real_stokeslet(r, ewald_xi) : stokeslet(r);
    const double r2 = r.squaredNorm(), rm = r.dot(m);
    double alpha, beta = 0.0;
    if (ewald_xi > 0) {
      const StressletSplitCoeffs c = ewald_real_stresslet_coeffs(std::sqrt(r2), ewald_xi);
      alpha = c.alpha;
      beta = c.beta;
    } else {
      alpha = -6.0 / (r2 * r2 * std::sqrt(r2));
    }
    // sum_k [alpha r_i r_j r_k + beta (d_ij r_k + d_jk r_i + d_ki r_j)] m_k
    Eigen::Matrix3d k = (alpha * rm) * r * r.transpose();
    k += beta * (rm * Eigen::Matrix3d::Identity() + r * m.transpose() + m * r.transpose());
    return k;
  }
};

}  // namespace rbcflow
