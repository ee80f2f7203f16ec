#pragma once
// Surface divergence of a Cartesian tensor field on a spherical-harmonic surface:
//   (div_s T)_j = a^alpha_i d(T_ij)/d theta^alpha,
// with a^alpha = a^{alpha beta} a_beta the contravariant tangents. For T = T^{ab} a_a (x) a_b
// + T^{a3} a_a (x) n this equals (T^{ab}_|a - b^b_a T^{a3}) a_b + (T^{a3}_|a + T^{ab} b_ab) n,
// the covariant divergence of the shell equations (22)-(23), without tensor components that
// are singular at the poles: each Cartesian component is a smooth function on the sphere and
// is differentiated spectrally.
#include <Eigen/Core>

#include "geometry/surface/sh_surface.h"
#include "geometry/sph/sph_transform.h"

namespace rbcflow {

// T: (grid size x 9) Cartesian components, column 3 i + j for T_ij. Analysed at the
// transform's full order on its (Gauss) grid, differentiated, contracted. Returns (size x 3).
Eigen::MatrixXd surface_divergence(const Eigen::MatrixXd& T, const SurfaceGeometry& g,
                                   const SHTransform& t);

// Contravariant tangents a^1, a^2 of the geometry (size x 3 each).
void contravariant_tangents(const SurfaceGeometry& g, SurfaceGeometry::Field3& up1,
                            SurfaceGeometry::Field3& up2);

}  // namespace rbcflow
