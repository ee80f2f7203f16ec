#pragma once
// The cells' volume centroids (geometry/surface/sh_surface.h), each computed by the rank that
// holds the cell's current shape and gathered on every rank: the branch monitor's passages
// (scenario/branch_monitor.h) and the Python module's centroids, without any rank reading a
// shape it does not hold or computing every cell's geometry (rank 0 did, every step, a serial
// cost that grew with the cells).
#include <Eigen/Core>
#include <vector>

#include "geometry/sph/sph_transform.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow {

// Every cell's volume centroid on the grid of `transform`, in cell order, on every rank: rank r
// computes those of holders' block r (holders.order[holders.first[r]] .. before [r + 1]) from
// their shapes alone and the ranks share them (share_blocks). The same bits on every rank and
// as on one. Collective.
std::vector<Eigen::Vector3d> volume_centroids(const std::vector<Cell>& cells, const SHTransform& transform,
                                              const CellOwners& holders, const Communicator& ranks);

}  // namespace rbcflow
