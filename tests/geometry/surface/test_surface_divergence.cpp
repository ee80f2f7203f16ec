#include "geometry/surface/surface_divergence.h"

#include <gtest/gtest.h>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

namespace {
const SHSurface& shape() {
  static const SHSurface s = make_squeezed_ellipsoid(32, squeezed_ellipsoid_default_rotation());
  return s;
}
}  // namespace

TEST(SurfaceDivergence, OfProjectionIsTwiceMeanCurvatureTimesNormal) {
  // div_s P = 2 H n on any surface (P = I - n n: unit isotropic tension). P is not
  // band-limited: its analysis on the M grid converges spectrally with M (de-aliasing).
  std::printf("  shape N = 32:  M   max relative error of div_s P - 2 H n\n");
  double prev = 1.0;
  for (int M : {32, 48, 64}) {
    const SHTransform t = SHTransform::gauss(M);
    const SurfaceGeometry g = shape().geometry(t);
    Eigen::MatrixXd P(g.size(), 9);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) P.col(3 * i + j) = (i == j ? 1.0 : 0.0) - (g.normal.col(i).array() * g.normal.col(j).array()).array();
    }
    const Eigen::MatrixXd d = surface_divergence(P, g, t);
    const Eigen::MatrixXd expected = g.normal.array().colwise() * (2.0 * g.mean_curvature.array());
    const double err = (d - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
    std::printf("                %2d   %.2e\n", M, err);
    EXPECT_LT(err, prev / 10);
    prev = err;
  }
  EXPECT_LT(prev, 1e-6);
}

TEST(SurfaceDivergence, OfScalarTimesIdentityIsSurfaceGradient) {
  // div_s(phi I) = grad_s phi; for phi = x_1 that is P e_1.
  const SHTransform t = SHTransform::gauss(32);
  const SurfaceGeometry g = shape().geometry(t);
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(g.size(), 9);
  for (int i = 0; i < 3; ++i) T.col(4 * i) = g.x.col(0);
  const Eigen::MatrixXd d = surface_divergence(T, g, t);
  for (int p = 0; p < g.size(); p += 13) {
    const Eigen::Vector3d n = g.normal.row(p);
    const Eigen::Vector3d expected = Eigen::Vector3d::UnitX() - n.x() * n;
    EXPECT_LT((Eigen::Vector3d(d.row(p)) - expected).norm(), 1e-10) << "point " << p;
  }
}
