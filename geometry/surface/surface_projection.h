#pragma once
// Projection of a point onto a spherical-harmonic surface: the foot point x(theta, phi)
// closest to x0, by Gauss-Newton on the spectral surface from a seed (a grid node near the
// closest point of the grid triangulation, found with an AABB tree).
#include <Eigen/Core>

#include "geometry/sph/sph_coeffs.h"

namespace rbcflow {

struct SurfaceProjection {
  double theta = 0, phi = 0;  // parameters of the foot point
  Eigen::Vector3d point;      // x(theta, phi)
  Eigen::Vector3d normal;     // outward unit normal there
  double distance = 0;        // |x0 - point|
  double signed_distance = 0; // > 0 outside (along the outward normal), < 0 inside
  bool converged = false;
  int iterations = 0;         // Newton iterations taken
};

// Newton iterations from (theta0, phi0) (Gauss-Newton while the Hessian of the squared
// distance is indefinite); updates move along the unit sphere of parameters
// (directions, not (theta, phi) directly) so that nothing special happens near the poles.
// A step is halved while it would take the foot point farther from x0, so the distance found
// is never more than the seed's: on a folded surface a full step could land on another sheet.
SurfaceProjection project_onto_surface(const SHCoeffs& x, const Eigen::Vector3d& x0, double theta0,
                                       double phi0, int max_iterations = 30);

}  // namespace rbcflow
