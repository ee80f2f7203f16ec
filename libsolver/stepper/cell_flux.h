#pragma once
// The cells' volume flux along a box axis: sum over cells of integral_V u_a dV, the volume times
// the mean velocity of each cell's interior (the rate of its volume centroid). The velocity is
// solenoidal inside a cell, so integral_V u_a dV = integral_S x_a (u . n) dS: the surface
// velocity on the cells' quadrature grid gives it exactly. Over a periodic tube of length L the
// cells' flux through the cross-sections averages to this sum / L, which over the tube's flux is
// the discharge hematocrit H_D (the tube's flux pi a^2 U).
#include <Eigen/Core>
#include <vector>

#include "geometry/surface/sh_surface.h"
#include "libsolver/parallel/communicator.h"

namespace rbcflow {

// `cells`: this rank's cells (every cell on one rank); `velocity`: their surface velocity,
// stacked in their order, in the point order of `grid`. On several `ranks` each sums its cells
// and the result is the ranks' sum (the same on every rank; another order of the sum than on
// one rank). Collective.
double cells_volume_flux(const std::vector<SHSurface>& cells, const Eigen::Ref<const Eigen::MatrixXd>& velocity, const SHTransform& grid,
                         int axis, const Communicator& ranks = {});

}  // namespace rbcflow
