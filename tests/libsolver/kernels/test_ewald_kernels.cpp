#include <gtest/gtest.h>

#include <numbers>

#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/kernels/stokes_kernels.h"

// The consistency of the real and Fourier halves (the sum does not depend on xi) is tested with
// the direct Ewald sum in tests/libsolver/spme/test_ewald_direct.cpp.

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;
const Eigen::Vector3d r0(0.31, -0.52, 0.17), q0(1.0, -0.4, 0.8), n0(0.2, 0.9, -0.3);
}  // namespace

TEST(EwaldKernels, RealStokesletFormula) {
  const double xi = 3.0, r = r0.norm();
  const double e = std::erfc(xi * r) / r, g = 2 * xi / std::sqrt(pi) * std::exp(-xi * xi * r * r);
  const Eigen::Matrix3d expected =
      (e - g) * Eigen::Matrix3d::Identity() + (e + g) * r0 * r0.transpose() / (r * r);
  EXPECT_LT((ewald_real_stokeslet(r0, xi) - expected).norm(), 1e-14);
  EXPECT_LT((ewald_real_stokeslet_apply(r0, xi, q0) - expected * q0).norm(), 1e-14);
}

// xi -> 0 puts everything in real space: S^R -> G, T^R -> T (errors O(xi)).
TEST(EwaldKernels, RealPartsTendToFreeSpaceKernelsAsXiVanishes) {
  const double xi = 1e-9;
  EXPECT_LT((ewald_real_stokeslet(r0, xi) - stokeslet(r0)).norm(), 1e-8);
  EXPECT_LT((ewald_real_stresslet_apply(r0, xi, q0, n0) - stresslet_apply(r0, q0, n0)).norm(),
            1e-8);
}

// Regular parts at r -> 0: S^R - G -> -(4 xi / sqrt(pi)) I (error O(xi^3 r^2)) and
// T^R - T -> (4 xi^3 / sqrt(pi)) (q (r.n) + n (r.q) + r (q.n)) (error O(xi^5 r^3)); checked at
// r = 1e-4 and 1e-3, where the cancellation of the 1/r and 1/r^2 terms costs ~1e-12 and ~1e-9.
TEST(EwaldKernels, RegularPartsAtTheOrigin) {
  const double xi = 2.0;
  const Eigen::Vector3d s = 1e-4 * r0.normalized();
  const Eigen::Matrix3d diff = ewald_real_stokeslet(s, xi) - stokeslet(s);
  EXPECT_LT((diff - ewald_real_stokeslet_self(xi) * Eigen::Matrix3d::Identity()).norm(), 1e-6);
  EXPECT_NEAR(ewald_real_stokeslet_self(xi), -4 * xi / std::sqrt(pi), 1e-15);
  const Eigen::Vector3d r = 1e-3 * r0.normalized();
  const Eigen::Vector3d t_diff =
      ewald_real_stresslet_apply(r, xi, q0, n0) - stresslet_apply(r, q0, n0);
  const Eigen::Vector3d t_limit =
      4 * xi * xi * xi / std::sqrt(pi) * (q0 * r.dot(n0) + n0 * r.dot(q0) + r * q0.dot(n0));
  EXPECT_LT((t_diff - t_limit).norm(), 1e-6);
}

// The contraction with (q, n) against the tensor alpha r r r + beta (delta r + ...).
TEST(EwaldKernels, RealStressletContraction) {
  const double xi = 1.7, r = r0.norm();
  const StressletSplitCoeffs c = ewald_real_stresslet_coeffs(r, xi);
  Eigen::Vector3d full = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double T = c.alpha * r0[i] * r0[j] * r0[k] +
                         c.beta * ((i == j) * r0[k] + (j == k) * r0[i] + (k == i) * r0[j]);
        full[i] += T * q0[j] * n0[k];
      }
  EXPECT_LT((ewald_real_stresslet_apply(r0, xi, q0, n0) - full).norm(), 1e-13);
  EXPECT_LT((ewald_real_stresslet_apply(-r0, xi, q0, n0) + full).norm(), 1e-13);  // odd
}

TEST(EwaldKernels, FourierStokesletIsScreenedAndSolenoidal) {
  const Eigen::Vector3d k(2 * pi, -4 * pi, 6 * pi);
  const double xi = 5.0, k2 = k.squaredNorm(),
               H = (1 + k2 / (4 * xi * xi)) * std::exp(-k2 / (4 * xi * xi));
  EXPECT_NEAR(ewald_fourier_scale(k2, xi), 8 * pi * H / k2, 1e-15);
  const Eigen::Vector3d u = ewald_fourier_stokeslet_apply(k, xi, q0);
  EXPECT_NEAR(k.dot(u), 0.0, 1e-14);
  EXPECT_LT((u - 8 * pi * H / k2 * (q0 - k * k.dot(q0) / k2)).norm(), 1e-14);
  EXPECT_NEAR(ewald_fourier_scale(k2, 1e9), 8 * pi / k2, 1e-12);  // no screening as xi -> inf
}

// d_k T_ijk = -8 pi delta_ij delta(r) in free space; screened: i k_k T^F_ijk = -8 pi H(k) delta_ij,
// i.e. T^F : (e_j, k) = i v with v = 8 pi H(k) e_j. And T^F is odd and symmetric in (q, n).
TEST(EwaldKernels, FourierStressletDivergenceAndSymmetry) {
  const Eigen::Vector3d k(2 * pi, 0.5 * pi, -3 * pi);
  const double xi = 4.0, k2 = k.squaredNorm();
  const double H = (1 + k2 / (4 * xi * xi)) * std::exp(-k2 / (4 * xi * xi));
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d v = ewald_fourier_stresslet_apply(k, xi, Eigen::Vector3d::Unit(j), k);
    EXPECT_LT((v - 8 * pi * H * Eigen::Vector3d::Unit(j)).norm(), 1e-13);
  }
  EXPECT_LT(
      (ewald_fourier_stresslet_apply(k, xi, q0, n0) - ewald_fourier_stresslet_apply(k, xi, n0, q0))
          .norm(),
      1e-14);
  EXPECT_LT(
      (ewald_fourier_stresslet_apply(-k, xi, q0, n0) + ewald_fourier_stresslet_apply(k, xi, q0, n0))
          .norm(),
      1e-14);
}
