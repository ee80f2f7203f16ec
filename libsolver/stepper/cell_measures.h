#pragma once
// What a frame reports of each cell at X^n (cells.csv): its volume centroid, its surface
// velocity's area-weighted mean, volume, area, Taylor deformation and the longest axis of its
// inertia ellipsoid (geometry/surface/inertia_ellipsoid.h). Each cell's are computed by the rank
// that owns it in the step's products, which holds its shape and its rows of U^n, and gathered
// on every rank: no rank reads a shape or a velocity it does not hold, and rank 0 no longer
// computes every cell's geometry and ellipsoid at every frame.
#include <Eigen/Core>
#include <vector>

#include "geometry/sph/sph_transform.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow {

struct CellMeasures {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // the area-weighted mean of U over the surface
  Eigen::Vector3d longest_axis = Eigen::Vector3d::Zero();  // the inertia ellipsoid's, a unit vector
  double volume = 0.0, area = 0.0, taylor_deformation = 0.0;
};

// Every cell's measures in cell order, on every rank, on the grid of `transform`: rank r
// computes those of owners' block r from their shapes and `owned_velocity` (the rows of those
// cells, in owner order, nodes x 3 each) and the ranks share them (share_blocks). The same bits
// on every rank and as on one. Collective. Throws std::invalid_argument when the owners or
// the rows do not fit the cells.
std::vector<CellMeasures> cell_measures(const std::vector<Cell>& cells, const SHTransform& transform,
                                        const Eigen::MatrixXd& owned_velocity, const CellOwners& owners,
                                        const Communicator& ranks);

}  // namespace rbcflow
