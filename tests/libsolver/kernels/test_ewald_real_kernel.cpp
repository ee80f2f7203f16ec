#include <gtest/gtest.h>

#include <cmath>

#include "libsolver/kernels/ewald_real_kernel.h"

using namespace rbcflow;

// The tabulated erfc against std::erfc over the table and beyond: measured relative error
// 5e-15 near x = 0 growing to 1.2e-14 at x = 8, as exp(-x^2) inherits the rounding of x^2 (the
// library's erfc avoids that with extra precision). Irrelevant next to any Ewald tolerance.
TEST(EwaldRealKernel, ErfcMatchesTheLibrary) {
  const EwaldRealKernel kernel(1.0);
  double worst = 0.0;
  for (int i = 0; i <= 200000; ++i) {
    const double x = 10.0 * i / 200000.0;
    double e, g;
    kernel.erfc_and_gaussian(x, e, g);
    worst = std::max(worst, std::abs(e - std::erfc(x)) / std::erfc(x));
    EXPECT_EQ(g, std::exp(-x * x));
  }
  EXPECT_LT(worst, 2e-14);
}

// Same kernels as ewald_kernels.h, from r -> 0 to xi r = 5.8 (beyond the cutoffs of every
// tolerance down to 1e-10, xi r_c <= 5.2).
TEST(EwaldRealKernel, KernelsMatchTheReferenceFormulas) {
  const double xi = 7.3;
  const EwaldRealKernel kernel(xi);
  const Eigen::Vector3d dir = Eigen::Vector3d(0.3, -0.8, 0.5).normalized();
  const Eigen::Vector3d q(1.0, 0.2, -0.7), n(0.1, 0.9, 0.4);
  for (double r : {1e-6, 1e-3, 0.05, 0.2, 0.5, 0.8}) {
    const Eigen::Vector3d x = r * dir;
    const Eigen::Vector3d s = kernel.stokeslet_apply(x, q),
                          s_ref = ewald_real_stokeslet_apply(x, xi, q);
    EXPECT_LE((s - s_ref).norm(), 1e-14 * s_ref.norm()) << r;
    const Eigen::Vector3d t = kernel.stresslet_apply(x, q, n),
                          t_ref = ewald_real_stresslet_apply(x, xi, q, n);
    EXPECT_LE((t - t_ref).norm(), 1e-14 * t_ref.norm()) << r;
  }
  EXPECT_THROW(EwaldRealKernel(0.0), std::invalid_argument);
}
