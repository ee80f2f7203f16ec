// Validation of the cell geometry against independent values: Carlson's elliptic integral for
// the ellipsoid area, Gauss-Bonnet, and the published Evans-Fung cell (Microvasc. Res. 4, 1972;
// docs/references.md section 6).
#include "geometry/surface/reference_shapes.h"

#include <gtest/gtest.h>

#include <boost/math/special_functions/ellint_rg.hpp>
#include <cmath>
#include <numbers>

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;
}

TEST(ReferenceShapes, EllipsoidAreaMatchesCarlsonAndVolumeIsExact) {
  const Eigen::Vector3d ax(0.8, 0.9, 1.0);
  // Surface area of an ellipsoid: 4 pi a b c R_G(1/a^2, 1/b^2, 1/c^2) (Carlson).
  const double exact_area =
      4 * pi * ax.prod() * boost::math::ellint_rg(1 / (ax[0] * ax[0]), 1 / (ax[1] * ax[1]), 1 / (ax[2] * ax[2]));
  const int N = 32;
  const SurfaceGeometry g = make_ellipsoid(N, ax).geometry(SHTransform::gauss(N));
  std::printf("  ellipsoid area %.15f, Carlson %.15f\n", surface_area(g), exact_area);
  EXPECT_NEAR(surface_area(g), exact_area, 1e-10 * exact_area);
  EXPECT_NEAR(enclosed_volume(g), 4 * pi * ax.prod() / 3, 1e-13);
}

TEST(ReferenceShapes, GaussBonnetOnSqueezedEllipsoidConvergesSpectrally) {
  std::printf("   N   |integral K dA - 4 pi|   area\n");
  double prev = 1.0;
  for (int N : {8, 12, 16, 24, 32}) {
    const SurfaceGeometry g =
        make_squeezed_ellipsoid(N, squeezed_ellipsoid_default_rotation()).geometry(SHTransform::gauss(N));
    const double err = std::abs(g.gaussian_curvature.dot(g.area_weight) - 4 * pi);
    std::printf("  %3d   %.3e            %.10f\n", N, err, surface_area(g));
    if (N >= 16) {
      EXPECT_LT(err, prev / 5) << "N = " << N << " did not improve spectrally";
    }
    prev = err;
    if (N == 32) {
      EXPECT_LT(err, 1e-8);
    }
  }
}

TEST(ReferenceShapes, EvansFungCellHasPublishedVolumeAndArea) {
  std::printf("   N   volume        area\n");
  for (int N : {8, 12, 16, 24, 32}) {
    const SurfaceGeometry g = make_biconcave(N).geometry(SHTransform::gauss(N));
    std::printf("  %3d   %.8f  %.8f\n", N, enclosed_volume(g), surface_area(g));
    if (N >= 16) {
      EXPECT_NEAR(enclosed_volume(g), 4.18879, 0.5e-5);  // to the digits of REFERENCES section 6
      EXPECT_NEAR(surface_area(g), 16.8431, 0.5e-4);
    }
  }
  EXPECT_NEAR(evans_fung_radius(), 1.385767, 1e-6);
  const SurfaceGeometry g = make_biconcave(32).geometry(SHTransform::gauss(32));
  const double v = enclosed_volume(g), a = surface_area(g);
  // Reduced volume 6 sqrt(pi) V / A^(3/2) = 0.64444.
  EXPECT_NEAR(6 * std::sqrt(pi) * v / std::pow(a, 1.5), 0.64444, 0.5e-5);
}
