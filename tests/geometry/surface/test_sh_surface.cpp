#include "geometry/surface/sh_surface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "geometry/surface/reference_shapes.h"

using namespace rbcflow;

namespace {
constexpr double pi = std::numbers::pi;
Eigen::Matrix3d some_rotation() {
  return (Eigen::AngleAxisd(1.2, Eigen::Vector3d(1, 2, 3).normalized())).toRotationMatrix();
}
}  // namespace

TEST(SHSurface, SphereHasExactAreaVolumeAndCurvatures) {
  for (double r : {0.5, 1.0, 2.7}) {
    const SHSurface s = make_sphere(12, r);
    const SHTransform t = SHTransform::gauss(12);
    const SurfaceGeometry g = s.geometry(t);
    EXPECT_NEAR(surface_area(g), 4 * pi * r * r, 1e-12 * r * r);
    EXPECT_NEAR(enclosed_volume(g), 4 * pi * r * r * r / 3, 1e-12 * r * r * r);
    // Sign convention: H = b^a_a / 2 = -1/r (b = -P/r), K = 1/r^2.
    EXPECT_LT((g.mean_curvature.array() + 1.0 / r).abs().maxCoeff(), 1e-12);
    EXPECT_LT((g.gaussian_curvature.array() - 1.0 / (r * r)).abs().maxCoeff(), 1e-12);
    // Outward normal: n = x / r.
    EXPECT_LT((g.normal - g.x / r).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(SHSurface, SphereFundamentalFormsAndChristoffelSymbols) {
  const double r = 1.5;
  const SHTransform t = SHTransform::gauss(8);
  const SurfaceGeometry g = make_sphere(8, r).geometry(t);
  for (int p = 0; p < g.size(); ++p) {
    const double th = t.grid().theta()[p / t.grid().n_phi()];
    const double s = std::sin(th), c = std::cos(th);
    EXPECT_NEAR(g.a11[p], r * r, 1e-12);
    EXPECT_NEAR(g.a12[p], 0.0, 1e-12);
    EXPECT_NEAR(g.a22[p], r * r * s * s, 1e-12);
    EXPECT_NEAR(g.b11[p], -r, 1e-12);
    EXPECT_NEAR(g.b22[p], -r * s * s, 1e-12);
    // Gamma^1_22 = -sin cos, Gamma^2_12 = cos / sin, all others zero.
    EXPECT_NEAR(g.christoffel[0][2][p], -s * c, 1e-12);
    EXPECT_NEAR(g.christoffel[1][1][p], c / s, 1e-11);
    EXPECT_NEAR(g.christoffel[0][0][p], 0.0, 1e-12);
    EXPECT_NEAR(g.christoffel[1][0][p], 0.0, 1e-12);
  }
}

TEST(SHSurface, RigidMotionsLeaveIntrinsicQuantitiesUnchanged) {
  const int N = 16;
  const SHTransform t = SHTransform::gauss(N);
  for (const SHSurface& shape : {make_biconcave(N), make_squeezed_ellipsoid(N, squeezed_ellipsoid_default_rotation())}) {
    SHSurface moved = shape;
    moved.rotate(some_rotation(), Eigen::Vector3d(0.3, -0.2, 0.1));
    moved.translate(Eigen::Vector3d(5.0, -1.0, 2.0));
    const SurfaceGeometry g0 = shape.geometry(t), g1 = moved.geometry(t);
    EXPECT_NEAR(surface_area(g1), surface_area(g0), 1e-12 * surface_area(g0));
    EXPECT_NEAR(enclosed_volume(g1), enclosed_volume(g0), 1e-12 * enclosed_volume(g0));
    const double hmax = g0.mean_curvature.cwiseAbs().maxCoeff();
    const double kmax = g0.gaussian_curvature.cwiseAbs().maxCoeff();
    EXPECT_LT((g1.mean_curvature - g0.mean_curvature).cwiseAbs().maxCoeff(), 1e-12 * hmax);
    EXPECT_LT((g1.gaussian_curvature - g0.gaussian_curvature).cwiseAbs().maxCoeff(), 1e-12 * kmax);
    // The normal rotates with the shape.
    EXPECT_LT((g1.normal - g0.normal * some_rotation().transpose()).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(SHSurface, CentroidAndInertiaOfTranslatedEllipsoid) {
  const Eigen::Vector3d axes(0.8, 0.9, 1.0), shift(1.0, 2.0, -3.0);
  SHSurface e = make_ellipsoid(8, axes);
  e.translate(shift);
  const SHTransform t = SHTransform::gauss(8);
  const SurfaceGeometry g = e.geometry(t);
  EXPECT_LT((volume_centroid(g) - shift).norm(), 1e-12);
  // Solid ellipsoid: I_xx = V (b^2 + c^2) / 5 etc.
  const double v = 4 * pi * axes.prod() / 3;
  const Eigen::Matrix3d inertia = inertia_tensor(g);
  EXPECT_NEAR(inertia(0, 0), v * (0.81 + 1.0) / 5, 1e-12);
  EXPECT_NEAR(inertia(1, 1), v * (0.64 + 1.0) / 5, 1e-12);
  EXPECT_NEAR(inertia(2, 2), v * (0.64 + 0.81) / 5, 1e-12);
  EXPECT_NEAR(inertia(0, 1), 0.0, 1e-12);
}

TEST(SHSurface, TriangulationIsClosedAndOutward) {
  double prev_err = 0.0;
  for (int N : {16, 32}) {
    const SHTransform t = SHTransform::gauss(N);
    const SHSurface s = make_biconcave(N);
    const TriangleMesh mesh = s.triangulate(t);
    EXPECT_EQ(mesh.num_points(), N * 2 * N + 2);
    EXPECT_EQ(mesh.num_triangles(), 2 * (2 * N) * N);  // closed: V - E + F = 2
    // Outward orientation gives a positive volume; linear triangles converge at second order.
    const double err = std::abs(enclosed_volume(mesh) - 4 * pi / 3);
    EXPECT_GT(enclosed_volume(mesh), 0.0);
    if (prev_err > 0) {
      EXPECT_GT(prev_err / err, 3.0) << "mesh volume error " << prev_err << " -> " << err;
    }
    prev_err = err;
    EXPECT_LT((s.north_pole() - Eigen::Vector3d(0, 0, 0.5 * evans_fung_radius() * 0.207161)).norm(), 1e-12);
  }
}

// The winding number of the triangulation is 1 inside and 0 outside, also in the dimple of a
// red cell (the centre, between the two faces 0.21 R apart) and just above it (in the hollow
// of the dimple, outside).
TEST(SHSurface, WindingNumberOfTheTriangulation) {
  const SHTransform t = SHTransform::gauss(16);
  const TriangleMesh mesh = make_biconcave(16).triangulate(t);
  const double half = 0.5 * evans_fung_radius() * 0.207161;  // half the thickness at the centre
  EXPECT_NEAR(winding_number(mesh, Eigen::Vector3d::Zero()), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(mesh, Eigen::Vector3d(0, 0, 0.8 * half)), 1.0, 1e-12);
  EXPECT_NEAR(winding_number(mesh, Eigen::Vector3d(0, 0, 1.3 * half)), 0.0, 1e-12);
  EXPECT_NEAR(winding_number(mesh, Eigen::Vector3d(0.9, 0.0, 0.0)), 1.0, 1e-12);  // in the rim
  EXPECT_NEAR(winding_number(mesh, Eigen::Vector3d(2.0, 0.3, -0.1)), 0.0, 1e-12);
}
