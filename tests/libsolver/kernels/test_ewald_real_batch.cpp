#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/kernels/ewald_real_batch.h"

using namespace rbcflow;

namespace {

// Separations from r = 1e-6 to xi r = 5.8 (beyond the cutoffs of every tolerance down to
// 1e-10, xi r_c <= 5.2) in varying directions; 1001 of them, so that the vector loops' last
// partial packet is exercised too.
struct Separations {
  std::vector<double> x, y, z;
};
Separations separations(double xi) {
  Separations s;
  const int n = 1001;
  for (int i = 0; i < n; ++i) {
    const double r = 1e-6 * std::pow(5.8 / xi / 1e-6, static_cast<double>(i) / (n - 1));
    const Eigen::Vector3d dir = Eigen::Vector3d(std::cos(0.7 * i), std::sin(1.3 * i), 0.4 - 0.001 * i).normalized();
    s.x.push_back(r * dir.x());
    s.y.push_back(r * dir.y());
    s.z.push_back(r * dir.z());
  }
  return s;
}

}  // namespace

// The vectorised coefficients applied as S^R f and T^R q n against ewald_kernels.h's formulas
// (std::erfc, std::exp): libmvec's erfc and exp are within 4 ulp (~1e-15) of the scalar
// functions, but exp(-xi^2 r^2) also inherits the rounding of its argument, which the two
// compute in different orders: up to ~2 ulp of xi^2 r^2 <= 33.6, a relative 33.6 x 2.2e-16 x 2
// = 1.5e-14 at the far end (measured: 7.0e-15 single, 7.3e-15 double layer, both at xi r = 5.1).
// Hence 2e-14 of the applied kernel's size, as for EwaldRealKernel's erfc. The vectors,
// not the coefficients, are compared: the Stokeslet's a changes sign near xi r = 0.7, where its
// own relative error means nothing.
TEST(EwaldRealBatch, CoefficientsMatchTheReferenceFormulas) {
  const double xi = 7.3;
  const Separations s = separations(xi);
  const int n = static_cast<int>(s.x.size());
  std::vector<double> a(n), b(n), alpha(n), beta(n);
  batch_stokeslet_coeffs(xi, s.x.data(), s.y.data(), s.z.data(), n, a.data(), b.data());
  batch_stresslet_coeffs(xi, s.x.data(), s.y.data(), s.z.data(), n, alpha.data(), beta.data());
  const Eigen::Vector3d f(1.0, 0.2, -0.7), q(0.3, -1.1, 0.5), nn(0.1, 0.9, 0.4);
  double worst_single = 0, worst_double = 0;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d r(s.x[i], s.y[i], s.z[i]);
    const Eigen::Vector3d single = a[i] * f + (b[i] * r.dot(f)) * r, single_ref = ewald_real_stokeslet_apply(r, xi, f);
    const double rq = r.dot(q), rn = r.dot(nn);
    const Eigen::Vector3d dbl = (alpha[i] * rq * rn + beta[i] * q.dot(nn)) * r + beta[i] * (rn * q + rq * nn);
    const Eigen::Vector3d dbl_ref = ewald_real_stresslet_apply(r, xi, q, nn);
    worst_single = std::max(worst_single, (single - single_ref).norm() / single_ref.norm());
    worst_double = std::max(worst_double, (dbl - dbl_ref).norm() / dbl_ref.norm());
  }
  EXPECT_LT(worst_single, 2e-14);
  EXPECT_LT(worst_double, 2e-14);
  std::printf("worst relative differences: single layer %.2e, double layer %.2e\n", worst_single, worst_double);
}
