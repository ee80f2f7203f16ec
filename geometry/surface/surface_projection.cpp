#include "geometry/surface/surface_projection.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/sph/sph_transform.h"

namespace rbcflow {
namespace {

Eigen::Vector3d direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

// The (theta, phi) chart is singular exactly at the poles: step off them by 1e-9 rad.
constexpr double kPoleOffset = 1e-9;
double off_pole(double theta) { return std::clamp(theta, kPoleOffset, std::numbers::pi - kPoleOffset); }

// The largest rotation of one step on the parameter sphere, and the rotation under which a step
// is taken even where it does not bring the foot point closer.
constexpr double kLargestRotation = 0.5;
constexpr double kSmallRotation = 1e-6;

}  // namespace

SurfaceProjection project_onto_surface(const SHCoeffs& x, const Eigen::Vector3d& x0, double theta0,
                                       double phi0, int max_iterations) {
  SurfaceProjection s;
  Eigen::Vector3d u = direction(theta0, phi0);
  double theta = off_pole(std::acos(std::clamp(u.z(), -1.0, 1.0)));
  double phi = std::atan2(u.y(), u.x());
  SHJet j = sh_evaluate_jet(x, theta, phi);
  for (int it = 0; it < max_iterations; ++it) {
    // Derivatives along the orthonormal directions e_theta, e_phi of the parameter sphere (the
    // local chart (theta + a, phi + b / sin(theta))).
    const double st = std::sin(theta);
    Eigen::Matrix<double, 3, 2> J;
    J.col(0) = j.x_t;
    J.col(1) = j.x_p / st;
    const Eigen::Vector3d r = j.x - x0;
    const Eigen::Vector2d g = J.transpose() * r;  // gradient of |x - x0|^2 / 2
    const Eigen::Matrix2d gauss_newton = J.transpose() * J;
    // Newton on |x - x0|^2 / 2 (quadratic convergence also off the surface, where Gauss-Newton
    // is only linear); Gauss-Newton where the Hessian is not positive definite (far away).
    Eigen::Matrix2d hessian = gauss_newton;
    hessian(0, 0) += r.dot(j.x_tt);
    hessian(0, 1) += r.dot(j.x_tp) / st;
    hessian(1, 0) = hessian(0, 1);
    hessian(1, 1) += r.dot(j.x_pp) / (st * st);
    const Eigen::LDLT<Eigen::Matrix2d> newton(hessian);
    const bool definite = newton.info() == Eigen::Success && newton.isPositive() && (newton.vectorD().array() > 0).all();
    const Eigen::Vector2d step = definite ? Eigen::Vector2d(-newton.solve(g)) : Eigen::Vector2d(-gauss_newton.ldlt().solve(g));
    const Eigen::Vector3d e_theta(std::cos(theta) * std::cos(phi), std::cos(theta) * std::sin(phi), -std::sin(theta));
    const Eigen::Vector3d e_phi(-std::sin(phi), std::cos(phi), 0.0);
    const double angle = step.norm();
    s.iterations = it + 1;
    if (angle > 0) {
      // Rotate u along the great circle in the step direction (keeps |u| = 1), halving the
      // rotation while it would take the foot point farther from x0: on a folded surface a full
      // step can land on another sheet, and the distance then found is not the closest (it
      // could be any size, on either side). Steps under kSmallRotation are in Newton's
      // quadratic regime, where round-off alone decides the comparison: taken as they are.
      const Eigen::Vector3d t = (step[0] * e_theta + step[1] * e_phi) / angle;
      double rotation = std::min(angle, kLargestRotation);
      for (;;) {
        const Eigen::Vector3d v = (std::cos(rotation) * u + std::sin(rotation) * t).normalized();
        const double v_theta = off_pole(std::acos(std::clamp(v.z(), -1.0, 1.0)));
        const double v_phi = std::atan2(v.y(), v.x());
        const SHJet k = sh_evaluate_jet(x, v_theta, v_phi);
        if ((k.x - x0).squaredNorm() <= r.squaredNorm() || rotation < kSmallRotation) {
          u = v;
          theta = v_theta;
          phi = v_phi;
          j = k;
          break;
        }
        rotation *= 0.5;
      }
    }
    // Iterate to round-off; converged once the steps are tiny (at a pole the 1e-9 offset
    // stops them there).
    s.converged = angle < 1e-9;
    if (angle < 1e-14) break;
  }
  s.theta = theta;
  s.phi = phi < 0 ? phi + 2 * std::numbers::pi : phi;
  s.point = j.x;
  s.normal = j.x_t.cross(j.x_p).normalized();
  s.distance = (x0 - s.point).norm();
  s.signed_distance = (x0 - s.point).dot(s.normal) >= 0 ? s.distance : -s.distance;
  return s;
}

}  // namespace rbcflow
