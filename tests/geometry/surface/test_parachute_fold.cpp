// The face-on fold of the red cell into a narrow tube (geometry/surface/parachute_fold.h). Exact: the
// volume (restored by a stretch along z, in which it is linear). Converging with the order: the
// area, which the equal-area map keeps exactly before the projection onto the cell's order
// smooths the parachute's rim (a curve with corners in its curvature).
#include "geometry/surface/parachute_fold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

namespace {

struct Measures {
  double volume, area;
  Eigen::Vector3d centroid;
  Eigen::MatrixXd x;
};

Measures measure(const SHSurface& s) {
  const SurfaceGeometry g = s.geometry(SHTransform::gauss(2 * s.order()));
  return {enclosed_volume(g), surface_area(g), volume_centroid(g), g.x};
}

}  // namespace

TEST(ParachuteFold, KeepsVolumeExactlyAndAreaAsTheOrderGrows) {
  std::printf("   N   R     radius  length  dimple  dV/V       dA/A\n");
  for (double R : {0.6, 0.76, 0.9}) {
    double previous = 1.0;
    for (int order : {12, 16, 24}) {
      const SHSurface disc = make_biconcave(order);
      const Measures before = measure(disc);
      const ParachuteFold f = fold_into_parachute(disc, R);
      const Measures after = measure(f.surface);
      const double dv = after.volume / before.volume - 1, da = after.area / before.area - 1;
      std::printf("  %2d  %.2f  %.4f  %.4f  %.4f  %9.2e  %+.4f\n", order, R, f.radius, f.length, f.dimple, dv, da);
      EXPECT_LT(std::abs(dv), 1e-12);
      EXPECT_LT(after.centroid.norm(), 1e-12);
      // Measured: |dA/A| 2.1%, 1.1%, 0.3% at N = 12, 16, 24 (R = 0.76); it must fall with N.
      EXPECT_LT(std::abs(da), 0.025);
      EXPECT_LT(std::abs(da), previous);
      previous = std::abs(da);
      // The projection's overshoot of the radius: about 1% (cell_placement corrects for it).
      EXPECT_LT(f.radius, 1.02 * R);
      EXPECT_GT(f.radius, 0.98 * R);
    }
  }
}

// The nose leads along +z: of the points near the axis (r < 0.2), the furthest along z is the
// nose, the nearest the dimple's centre, well between the rear and the nose; the rim (the
// widest ring) is in the rear half.
TEST(ParachuteFold, NoseForwardDimpleBehindRimAtTheRear) {
  const ParachuteFold f = fold_into_parachute(make_biconcave(16), 0.76);
  const Measures m = measure(f.surface);
  const Eigen::VectorXd r = m.x.leftCols<2>().rowwise().norm();
  const double top = m.x.col(2).maxCoeff(), bottom = m.x.col(2).minCoeff();
  double nose = -1e9, dimple = 1e9;
  for (int p = 0; p < m.x.rows(); ++p)
    if (r[p] < 0.2) nose = std::max(nose, m.x(p, 2)), dimple = std::min(dimple, m.x(p, 2));
  int widest = 0;
  r.maxCoeff(&widest);
  std::printf("nose %.4f, dimple %.4f, rim %.4f, extent [%.4f, %.4f]\n", nose, dimple, m.x(widest, 2), bottom, top);
  EXPECT_NEAR(nose, top, 0.02);
  EXPECT_GT(dimple, bottom + 0.3);  // a real dimple: well above the rim's trailing edge
  EXPECT_LT(dimple, nose - 0.3);    // and a real nose ahead of it
  EXPECT_LT(m.x(widest, 2), 0.5 * (top + bottom));
}

// A radius so large that a parachute holding the cell's volume has more than its area (the
// cell would not need folding), or so small that it has too (a long thin tube): errors that say
// which.
TEST(ParachuteFold, TooWideOrTooNarrowARadiusIsAnError) {
  for (const auto& [R, says] : {std::pair{1.6, "too large"}, std::pair{0.45, "too small"}}) {
    try {
      fold_into_parachute(make_biconcave(12), R);
      FAIL() << "no parachute of radius " << R << " has the red cell's area and volume";
    } catch (const std::runtime_error& e) {
      std::printf("%s\n", e.what());
      EXPECT_NE(std::string(e.what()).find(says), std::string::npos);
    }
  }
}
