#include "libsolver/quadrature/polar_patch.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

using namespace rbcflow;

namespace {
// Great-circle distance between two points of the unit sphere given by their parameters.
double great_circle_distance(double theta1, double phi1, double theta2, double phi2) {
  // Haversine-free but accurate form: atan2(|u1 x u2|, u1 . u2).
  const Eigen::Vector3d u1(std::sin(theta1) * std::cos(phi1), std::sin(theta1) * std::sin(phi1), std::cos(theta1));
  const Eigen::Vector3d u2(std::sin(theta2) * std::cos(phi2), std::sin(theta2) * std::sin(phi2), std::cos(theta2));
  return std::atan2(u1.cross(u2).norm(), u1.dot(u2));
}
}  // namespace

TEST(PolarPatch, MaskIsOneAtCentreZeroAtEdgeAndMonotone) {
  EXPECT_DOUBLE_EQ(patch_mask(0.0, 0.5), 1.0);
  EXPECT_DOUBLE_EQ(patch_mask(0.5, 0.5), 0.0);
  EXPECT_DOUBLE_EQ(patch_mask(0.7, 0.5), 0.0);
  double prev = 1.0;
  for (double r = 0.01; r < 0.5; r += 0.01) {
    EXPECT_LE(patch_mask(r, 0.5), prev);
    prev = patch_mask(r, 0.5);
  }
  // 1 - eta vanishes faster than any power at the centre (it kills the kernel's singularity).
  EXPECT_LT(1.0 - patch_mask(0.02, 0.5), 1e-10);
}

TEST(PolarPatch, IntegratesTheMaskOverTheSphereExactly) {
  // sum of weights = integral over the cap of eta dOmega = 2 pi integral eta(rho) sin(rho) drho,
  // compared with a fine trapezoid rule; anywhere on the sphere, with or without sinh clustering.
  const double rho1 = 1.1;
  double reference = 0.0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double r = (i + 0.5) * rho1 / n;
    reference += patch_mask(r, rho1) * std::sin(r) * rho1 / n;
  }
  reference *= 2 * std::numbers::pi;
  for (double delta : {0.0, 0.01}) {
    for (auto [t, p] : {std::pair{0.0, 0.0}, {1.0, 2.0}, {3.1, 6.0}}) {
      double sum = 0.0;
      for (const PatchPoint& q : polar_patch(t, p, rho1, 40, 16, delta)) sum += q.weight;
      // The sinh map spends its points near the centre: the smooth bulk is less resolved.
      EXPECT_NEAR(sum, reference, delta > 0 ? 1e-6 : 1e-9) << "delta " << delta;
    }
  }
}

TEST(PolarPatch, PointsLieAtTheirDistanceFromTheCentre) {
  for (const PatchPoint& q : polar_patch(0.8, 1.3, 0.6, 6, 8, 0.05)) {
    EXPECT_NEAR(great_circle_distance(0.8, 1.3, q.theta, q.phi), q.rho, 1e-12);
    EXPECT_LT(q.rho, 0.6);
  }
}
