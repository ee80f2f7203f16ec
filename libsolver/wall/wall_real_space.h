#pragma once
// The real-space part of the periodic wall single layer (section 5.3, eq. 24) as a sparse
// matrix acting on nodal force densities (3 n_targets x 3 n_nodes, index 3 i + k, like
// NearField): entry block (t, node a of triangle T) = sum over the Gauss points q of T within
// the cutoff of target t of S^R(y_q - x_t) w_q lambda_a(q). Built once for targets that never
// move (the wall nodes of the wall solve), it turns the real-space sum of every product into
// one sparse product over nodes instead of a kernel evaluation per (target, Gauss point) pair.
#include <Eigen/SparseCore>

#include "libsolver/spme/neighbor_list.h"
#include "wall_elements.h"

namespace rbcflow {

// `pairs`: the neighbour list of the Ewald plan whose sources are the Gauss points of
// `elements` (row 7 T + q) and whose targets are the operator's.
Eigen::SparseMatrix<double> wall_real_space_matrix(const WallElements& elements, const NeighborList& pairs, double xi);

}  // namespace rbcflow
