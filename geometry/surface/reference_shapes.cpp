#include "geometry/surface/reference_shapes.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace rbcflow {
namespace {

constexpr double kEvansFungC0 = 0.207161;
constexpr double kEvansFungC1 = 2.002558;
constexpr double kEvansFungC2 = -1.122762;

}  // namespace

SHSurface surface_from_map(int order, const SphereMap& map) {
  const SHTransform t(2 * order, SphGrid::gauss(2 * order), 0);
  const SphGrid& g = t.grid();
  Eigen::MatrixXd values(g.size(), 3);
  for (int i = 0; i < g.n_theta(); ++i) {
    const double st = std::sin(g.theta()[i]), ct = std::cos(g.theta()[i]);
    for (int j = 0; j < g.n_phi(); ++j) {
      const Eigen::Vector3d u(st * std::cos(g.phi(j)), st * std::sin(g.phi(j)), ct);
      values.row(i * g.n_phi() + j) = map(u).transpose();
    }
  }
  return SHSurface(t.analyze(values, order));
}

SHSurface make_sphere(int order, double radius) {
  return surface_from_map(order, [radius](const Eigen::Vector3d& u) { return Eigen::Vector3d(radius * u); });
}

SHSurface make_ellipsoid(int order, const Eigen::Vector3d& semi_axes) {
  return surface_from_map(order, [semi_axes](const Eigen::Vector3d& u) {
    return Eigen::Vector3d(semi_axes.cwiseProduct(u));
  });
}

double evans_fung_radius() {
  // Volume = 2 pi R0^3 integral_0^1 s sqrt(1 - s^2)(c0 + c1 s^2 + c2 s^4) ds
  //        = 2 pi R0^3 (c0/3 + 2 c1/15 + 8 c2/105); set equal to 4 pi / 3.
  const double shape = kEvansFungC0 / 3.0 + 2.0 * kEvansFungC1 / 15.0 + 8.0 * kEvansFungC2 / 105.0;
  return std::cbrt((4.0 * std::numbers::pi / 3.0) / (2.0 * std::numbers::pi * shape));
}

SHSurface make_biconcave(int order) {
  const double r0 = evans_fung_radius();
  return surface_from_map(order, [r0](const Eigen::Vector3d& u) {
    // r = R0 sin(theta), sqrt(1 - s^2) = |cos(theta)|, the sign of z that of cos(theta) = u_z.
    const double s2 = 1.0 - u.z() * u.z();
    const double z = 0.5 * r0 * u.z() * (kEvansFungC0 + kEvansFungC1 * s2 + kEvansFungC2 * s2 * s2);
    return Eigen::Vector3d(r0 * u.x(), r0 * u.y(), z);
  });
}

SHSurface make_squeezed_ellipsoid(int order, const Eigen::Matrix3d& pole_rotation) {
  return surface_from_map(order, [pole_rotation](const Eigen::Vector3d& u) {
    constexpr double a = 0.8, b = 0.9, c = 1.0;
    const Eigen::Vector3d v = pole_rotation * u;  // direction in the ellipsoid's own frame
    const double z = c * v.z();
    const double s = 1.0 - 0.7 * std::cos(0.5 * std::numbers::pi * (z / c + 0.2));
    return Eigen::Vector3d(a * s * v.x(), b * s * v.y(), z);
  });
}

Eigen::Matrix3d squeezed_ellipsoid_default_rotation() {
  return (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(0.9, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

}  // namespace rbcflow
