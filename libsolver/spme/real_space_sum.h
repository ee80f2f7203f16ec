#pragma once
// Real-space parts of the Ewald sums (eq. 24 and 27) over the pairs of a NeighborList, r = 0
// pairs excluded (see neighbor_list.h). Parallel over targets (OpenMP).
#include <vector>

#include "neighbor_list.h"
#include "periodic_box.h"

namespace rbcflow {

// Both sums split each kernel into two radial coefficients (a f + b (r.f) r for S^R; alpha and
// beta of StressletSplitCoeffs for T^R). `coefficients`, when given, keeps them per pair for
// products with the same list: filled by the first product (empty on entry), read by the
// next ones, which then cost a few flops per pair instead of a kernel evaluation.

// u_t = sum_{pairs (s, n)} S^R(x_s + n L - x_t) f_s, one row per target.
PointField real_space_single_layer(const NeighborList& pairs, double xi, const PointField& forces,
                                   std::vector<double>* coefficients = nullptr);

// u_t,i = sum_{pairs (s, n)} T^R_ijk(x_s + n L - x_t) q_s,j n_s,k.
PointField real_space_double_layer(const NeighborList& pairs, double xi, const PointField& q,
                                   const PointField& normals, std::vector<double>* coefficients = nullptr);

}  // namespace rbcflow
