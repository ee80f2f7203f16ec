#pragma once
// Reference cell shapes as spherical-harmonic surfaces, each the image of the unit sphere
// under a smooth map u -> x(u), sampled and analysed on a Gauss grid.
#include <Eigen/Core>
#include <functional>

#include "geometry/surface/sh_surface.h"

namespace rbcflow {

using SphereMap = std::function<Eigen::Vector3d(const Eigen::Vector3d& unit_direction)>;

// Coefficients (order N) of the surface x(u) = map(u), u the unit vector of (theta, phi).
// Sampled on a Gauss grid of order 2N so that truncation, not aliasing, sets the error.
SHSurface surface_from_map(int order, const SphereMap& map);

SHSurface make_sphere(int order, double radius = 1.0);
SHSurface make_ellipsoid(int order, const Eigen::Vector3d& semi_axes);

// Evans & Fung (Microvasc. Res. 4, 1972) biconcave disc, symmetry axis along z:
// z(r) = +-(1/2) R0 sqrt(1 - s^2) (c0 + c1 s^2 + c2 s^4), s = r / R0, scaled so that its
// volume is that of the unit sphere (equivalent radius a = 1). A polynomial of degree 5 in u:
// exact for N >= 6.
SHSurface make_biconcave(int order);
// R0 of the scaled Evans-Fung disc (1.385767...).
double evans_fung_radius();

// The squeezed ellipsoid of section 8: x^2/(a s)^2 + y^2/(b s)^2 + z^2/c^2 = 1 with
// s(z) = 1 - 0.7 cos(pi/2 (z/c + 0.2)), (a, b, c) = (0.8, 0.9, 1.0), parametrised so that the
// grid's poles are rotated away from the ellipsoid's axes by `pole_rotation`.
SHSurface make_squeezed_ellipsoid(int order, const Eigen::Matrix3d& pole_rotation);
// The default pole rotation used by the tests of section 8 (a generic, fixed rotation).
Eigen::Matrix3d squeezed_ellipsoid_default_rotation();

}  // namespace rbcflow
