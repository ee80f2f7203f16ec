#pragma once
// Real-space parts of the Ewald sums (eq. 24 and 27) over the pairs of a NeighborList, r = 0
// pairs excluded (see neighbor_list.h). Parallel over targets (OpenMP).
#include "neighbor_list.h"
#include "periodic_box.h"

namespace rbcflow {

// u_t = sum_{pairs (s, n)} S^R(x_s + n L - x_t) f_s, one row per target.
PointField real_space_single_layer(const NeighborList& pairs, double xi, const PointField& forces);

// u_t,i = sum_{pairs (s, n)} T^R_ijk(x_s + n L - x_t) q_s,j n_s,k.
PointField real_space_double_layer(const NeighborList& pairs, double xi, const PointField& q,
                                   const PointField& normals);

}  // namespace rbcflow
