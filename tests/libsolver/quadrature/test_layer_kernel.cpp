#include <gtest/gtest.h>

#include <Eigen/Core>

#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/kernels/stokes_kernels.h"
#include "libsolver/quadrature/layer_kernel.h"

using namespace rbcflow;

namespace {

// K(r) applied to the unit vectors, column by column, from the reference formulas of
// ewald_kernels.h (std::erfc) or the free-space kernels.
Eigen::Matrix3d reference(Layer layer, double xi, const Eigen::Vector3d& r, const Eigen::Vector3d& m) {
  Eigen::Matrix3d k;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(j);
    if (layer == Layer::single) {
      k.col(j) = xi > 0 ? ewald_real_stokeslet_apply(r, xi, e) : Eigen::Vector3d(stokeslet(r) * e);
    } else {
      k.col(j) = xi > 0 ? ewald_real_stresslet_apply(r, xi, e, m) : stresslet_apply(r, e, m);
    }
  }
  return k;
}

}  // namespace

// The correction builds evaluate the Ewald real-space kernels with EwaldRealKernel's tabulated
// erfc (relative error <= 1.2e-14, test_ewald_real_kernel): the matrices must agree with the
// reference formulas to that level from r -> 0 to beyond any real-space cutoff (xi r = 5.8),
// and reduce to the free-space kernels at xi = 0.
TEST(LayerKernel, MatricesMatchTheReferenceKernels) {
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const Eigen::Vector3d m(0.1, 0.9, 0.4);
  for (Layer layer : {Layer::single, Layer::double_}) {
    for (double xi : {0.0, 1.3, 7.3}) {
      const LayerKernel kernel(layer, xi);
      for (double r : {1e-6, 1e-3, 0.05, 0.2, 0.5, 0.8}) {
        const Eigen::Vector3d x = r * dir;
        const Eigen::Matrix3d k = kernel.matrix(x, m), k_ref = reference(layer, xi, x, m);
        EXPECT_LE((k - k_ref).norm(), 3e-14 * k_ref.norm()) << "layer " << int(layer) << " xi " << xi << " r " << r;
        EXPECT_LE((k - k.transpose()).norm(), 1e-15 * k.norm());
      }
    }
  }
}
