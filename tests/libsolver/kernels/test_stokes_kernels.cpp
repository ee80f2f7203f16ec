#include <gtest/gtest.h>

#include <numbers>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/kernels/stokes_kernels.h"

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;

// d/dr_m G_ij by central differences.
double d_stokeslet(const Eigen::Vector3d& r, int i, int j, int m) {
  const double h = 1e-5;
  const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(m);
  return (stokeslet(r + e)(i, j) - stokeslet(r - e)(i, j)) / (2 * h);
}
}  // namespace

TEST(StokesKernels, StokesletFormulaAndApply) {
  const Eigen::Vector3d r(0.3, -0.7, 1.1), f(1.0, 2.0, -0.5);
  const double rn = r.norm();
  const Eigen::Matrix3d G = stokeslet(r);
  EXPECT_LT((G - G.transpose()).norm(), 1e-15);
  EXPECT_NEAR(G(0, 1), r[0] * r[1] / (rn * rn * rn), 1e-15);
  EXPECT_NEAR(G(2, 2), 1 / rn + r[2] * r[2] / (rn * rn * rn), 1e-15);
  EXPECT_LT((stokeslet_apply(r, f) - G * f).norm(), 1e-14);
  EXPECT_LT((stokeslet(-r) - G).norm(), 1e-15);  // even
}

TEST(StokesKernels, StokesletIsDivergenceFree) {
  const Eigen::Vector3d r(0.4, 0.2, -0.9);
  for (int i = 0; i < 3; ++i) {
    double div = 0;
    for (int j = 0; j < 3; ++j) div += d_stokeslet(r, i, j, j);
    EXPECT_NEAR(div, 0.0, 1e-8);
  }
}

// T is the stress of the Stokeslet (eq. 2): T_ijk = -P_j delta_ik + d_k G_ij + d_i G_kj with
// the pressure P_j = 2 r_j / r^3, all derivatives with respect to r.
TEST(StokesKernels, StressletIsTheStressOfTheStokeslet) {
  const Eigen::Vector3d r(0.4, 0.2, -0.9);
  const double r3 = std::pow(r.norm(), 3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const double expected =
            -(i == k ? 2 * r[j] / r3 : 0.0) + d_stokeslet(r, i, j, k) + d_stokeslet(r, k, j, i);
        EXPECT_NEAR(stresslet(r, i, j, k), expected, 1e-8) << i << j << k;
      }
  const Eigen::Vector3d q(1, -2, 0.5), n(0.3, 0.1, 0.7);
  Eigen::Vector3d full = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) full[i] += stresslet(r, i, j, k) * q[j] * n[k];
  EXPECT_LT((stresslet_apply(r, q, n) - full).norm(), 1e-13);
  EXPECT_LT((stresslet_apply(-r, q, n) + full).norm(), 1e-13);  // odd
}

// docs/references.md section 1 in free space, sphere of radius 0.7, x = surface, x0 = target:
// integral G(x - x0) n dS = 0; integral T_ijk(x - x0) n_k dS = -8 pi delta_ij inside, 0 outside.
TEST(StokesKernels, FreeSpaceLayerIdentitiesOnASphere) {
  const int N = 48;
  const SHTransform t = SHTransform::gauss(N);
  const SurfaceGeometry g = make_sphere(N, 0.7).geometry(t);
  for (const auto& [x0, inside] : {std::pair{Eigen::Vector3d(0.1, -0.2, 0.15), true},
                                   std::pair{Eigen::Vector3d(1.2, 0.3, -0.4), false}}) {
    Eigen::Vector3d single = Eigen::Vector3d::Zero();
    Eigen::Matrix3d dbl = Eigen::Matrix3d::Zero();
    for (int p = 0; p < g.size(); ++p) {
      const Eigen::Vector3d r = g.x.row(p).transpose() - x0, n = g.normal.row(p).transpose();
      single += g.area_weight[p] * stokeslet_apply(r, n);
      for (int j = 0; j < 3; ++j)
        dbl.col(j) += g.area_weight[p] * stresslet_apply(r, Eigen::Vector3d::Unit(j), n);
    }
    EXPECT_LT(single.norm(), 1e-11);
    const double expected = inside ? -8 * pi : 0.0;
    EXPECT_LT((dbl - expected * Eigen::Matrix3d::Identity()).norm(), 1e-10) << dbl;
  }
}
