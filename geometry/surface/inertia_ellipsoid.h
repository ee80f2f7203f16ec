#pragma once
// The ellipsoid with the volume's inertia tensor (unit density): for semi-axes a_i,
// I_i = (V / 5)(a_j^2 + a_k^2), so a_i^2 = (5 / (2V))(I_j + I_k - I_i). Its axes give the
// Taylor deformation (L - B) / (L + B) and the inclination of a deformed cell.
#include <Eigen/Core>

#include "geometry/surface/sh_surface.h"

namespace rbcflow {

struct InertiaEllipsoid {
  Eigen::Vector3d semi_axes;  // ascending
  Eigen::Matrix3d axes;       // unit directions, column i for semi_axes[i]
  double taylor_deformation() const { return (semi_axes[2] - semi_axes[0]) / (semi_axes[2] + semi_axes[0]); }
};

InertiaEllipsoid inertia_ellipsoid(const SurfaceGeometry& g);

}  // namespace rbcflow
