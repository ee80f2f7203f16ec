#pragma once
// The kernel of a boundary-integral layer as a 3x3 matrix acting on the density:
//   single layer (4):  K(r) = G(r) (free space) or S^R(r) (Ewald real-space part, eq. 24)
//   double layer (5):  K(r)_ij = sum_k T_ijk(r) m_k, m the area-weighted normal
//                      (free space or Ewald real-space T^R, eq. 27),
// with r = x - x0 (source minus target). Both matrices are symmetric. xi = 0 selects the
// free-space kernels; xi > 0 the real-space part of Hasimoto's split with that xi, evaluated
// with the tabulated erfc of EwaldRealKernel (the correction builds evaluate it at every
// patch point).
#include <Eigen/Core>
#include <cmath>
#include <optional>

#include "libsolver/kernels/ewald_real_kernel.h"
#include "libsolver/kernels/stokes_kernels.h"

namespace rbcflow {

enum class Layer { single, double_ };

class LayerKernel {
 public:
  LayerKernel() = default;
  LayerKernel(Layer layer, double ewald_xi) : layer_(layer) {
    if (ewald_xi > 0) real_.emplace(ewald_xi);
  }

  Layer layer() const { return layer_; }

  // K(r) for a source of area-weighted normal m (unused by the single layer).
  Eigen::Matrix3d matrix(const Eigen::Vector3d& r, const Eigen::Vector3d& m) const {
    if (layer_ == Layer::single) return real_ ? real_->stokeslet_matrix(r) : stokeslet(r);
    const double r2 = r.squaredNorm(), rm = r.dot(m);
    double alpha, beta = 0.0;
    if (real_) {
      const StressletSplitCoeffs c = real_->stresslet_coeffs(std::sqrt(r2));
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

 private:
  Layer layer_ = Layer::single;
  std::optional<EwaldRealKernel> real_;  // set for xi > 0
};

}  // namespace rbcflow
