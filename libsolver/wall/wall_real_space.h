#pragma once
// The real-space part of the periodic wall single layer (section 5.3, eq. 24) as a sparse
// matrix acting on nodal force densities (3 n_targets x 3 n_nodes, index 3 i + k, like
// NearField): entry block (t, node a of triangle T) = sum over the Gauss points q of T within
// the cutoff of target t of S^R(y_q - x_t) w_q lambda_a(q). Built once for targets that never
// move (the wall nodes of the wall solve), it turns the real-space sum of every product into
// one sparse product over nodes instead of a kernel evaluation per (target, Gauss point) pair.
#include <Eigen/SparseCore>

#include "libsolver/parallel/owned_rows.h"
#include "libsolver/parallel/ownership.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/spme/neighbor_list.h"
#include "symmetric_block_matrix.h"
#include "wall_elements.h"

namespace rbcflow {

// The Ewald cost model of this matrix (ewald_parameters.h): a (target, Gauss point) pair costs
// about 1/100 of a kernel evaluation per product (the matrix holds one 3x3 block per (target,
// node) pair, a 14th as many as Gauss pairs, applied at ~1 ns per entry, and its assembly is
// spread over every GMRES product of a run); at most 5e7 pairs (~0.6 GB of matrix). Measured
// on the minicase (bench_step): weights 1, 0.1, 0.025, 0.01 gave 0.71, 0.32, 0.32, 0.26 s per
// wall solve of 9 iterations.
inline constexpr RealSpaceUse kAssembledRealSpace{0.01, 5e7};
// The error estimates assume uncorrelated sources; the smooth densities of a wall add up
// coherently over the large cutoff this choice makes, and the measured error exceeded the
// tolerance up to 7x (tests/libsolver/wall/test_wall_real_space.cpp). The assembled operator
// therefore asks the chooser for a tenth of the user's tolerance (and then meets it).
inline constexpr double kAssembledToleranceFactor = 0.1;

// `pairs`: the neighbour list of the Ewald plan whose sources are the Gauss points of
// `elements` (row 7 T + q) and whose targets are the operator's.
Eigen::SparseMatrix<double> wall_real_space_matrix(const WallElements& elements, const NeighborList& pairs, double xi);
// The same plus `plus` (the near-field correction: NearField::correction) as symmetric blocks,
// assembled row by row: the operator's form (wall_operator.h), without the scalar matrices in
// between, which took ten times its memory at the peak of the set-up. Only the targets in
// `rows` get their blocks (a rank's share, parallel/ownership.h); the others' rows stay empty.
SymmetricBlockMatrix wall_real_space_blocks(
    const WallElements& elements, const NeighborList& pairs, double xi,
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& plus, OwnedRange rows,
    SymmetricBlockMatrix::Precision precision = SymmetricBlockMatrix::Precision::double_entries);
// The same for the targets of this rank's segment (the wall nodes of the wall solve).
SymmetricBlockMatrix wall_real_space_blocks(
    const WallElements& elements, const NeighborList& pairs, double xi,
    const Eigen::SparseMatrix<double, Eigen::RowMajor>& plus, const OwnedSegments& rows,
    SymmetricBlockMatrix::Precision precision = SymmetricBlockMatrix::Precision::double_entries);

}  // namespace rbcflow
