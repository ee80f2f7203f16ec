#include "surface_projection.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "sph_transform.h"

namespace rbcflow {
namespace {

Eigen::Vector3d direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// The (theta, phi) chart is singular exactly at the poles: step off them by 1e-9 rad.
constexpr double kPoleOffset = 1e-9;
double off_pole(double theta) { return std::clamp(theta, kPoleOffset, std::numbers::pi - kPoleOffset); }

}  // namespace

SurfaceProjection project_onto_surface(const SHCoeffs& x, const Eigen::Vector3d& x0, double theta0,
                                       double phi0, int max_iterations) {
  SurfaceProjection s;
  Eigen::Vector3d u = direction(theta0, phi0);
  for (int it = 0; it < max_iterations; ++it) {
    const double theta = off_pole(std::acos(std::clamp(u.z(), -1.0, 1.0)));
    const double phi = std::atan2(u.y(), u.x());
    const Eigen::Vector3d p = sh_evaluate(x, theta, phi).transpose();
    // Derivatives along the orthonormal directions e_theta, e_phi of the parameter sphere.
    const double st = std::sin(theta);
    Eigen::Matrix<double, 3, 2> J;
    J.col(0) = sh_evaluate(x, theta, phi, 1, 0).transpose();
    J.col(1) = sh_evaluate(x, theta, phi, 0, 1).transpose() / st;
    const Eigen::Vector2d step = (J.transpose() * J).ldlt().solve(J.transpose() * (x0 - p));
    const Eigen::Vector3d e_theta(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), -std::sin(theta));
    const Eigen::Vector3d e_phi(-std::sin(phi), std::cos(phi), 0.0);
    // Rotate u along the great circle in the step direction (keeps |u| = 1).
    const double angle = step.norm();
    if (angle > 0) {
      const Eigen::Vector3d t = (step[0] * e_theta + step[1] * e_phi) / angle;
      u = std::cos(std::min(angle, 0.5)) * u + std::sin(std::min(angle, 0.5)) * t;
      u.normalize();
    }
    // Gauss-Newton converges linearly off the surface: iterate to round-off, and call it
    // converged once the steps are tiny (at a pole the 1e-9 offset stops them there).
    s.converged = angle < 1e-9;
    if (angle < 1e-14) break;
  }
  s.theta = off_pole(std::acos(std::clamp(u.z(), -1.0, 1.0)));
  s.phi = std::atan2(u.y(), u.x());
  if (s.phi < 0) s.phi += 2 * std::numbers::pi;
  s.point = sh_evaluate(x, s.theta, s.phi).transpose();
  const Eigen::Vector3d a1 = sh_evaluate(x, s.theta, s.phi, 1, 0).transpose();
  const Eigen::Vector3d a2 = sh_evaluate(x, s.theta, s.phi, 0, 1).transpose();
  s.normal = a1.cross(a2).normalized();
  s.distance = (x0 - s.point).norm();
  s.signed_distance = (x0 - s.point).dot(s.normal) >= 0 ? s.distance : -s.distance;
  return s;
}

}  // namespace rbcflow
