#pragma once
// Real-space parts of the Ewald sums (eq. 24 and 27) over the pairs of a NeighborList, r = 0
// pairs excluded (see neighbor_list.h). Parallel over targets (OpenMP).
#include <cstdint>
#include <vector>

#include "neighbor_list.h"
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

// Pairs that count with weight 1 - share: the part of their integral that another rule supplies
// (the patches of the singular quadrature, where the regular rule's share is eta, the
// partition of unity: quadrature/singular_quadrature.h). CSR over the caller's targets:
// offsets[t] .. offsets[t + 1] index sources (the caller's indices) and shares; a source may
// appear more than once (the shares add). A pair is weighted at its nearest image only, which
// must lie within the cutoff and within half the shortest box side (else it is not weighted).
// Empty offsets: no weighted pair. The shares are kept in single precision (8 bytes a pair
// with the source against 12), as the singular corrections keep their eta (singular_quadrature.h
// PatchNode).
struct PairShares {
  std::vector<std::int64_t> offsets;
  std::vector<int> sources;
  std::vector<float> shares;
};

// Pairs closer than this are in a list of this cutoff at their nearest image, whatever the
// rounding of the wrapped positions: where PairShares may name them.
double pair_share_radius(const PeriodicBox& box, double cutoff);

// Both sums split each kernel into two radial coefficients (a f + b (r.f) r for S^R; alpha and
// beta of StressletSplitCoeffs for T^R). `coefficients`, when given, keeps them per pair for
// products with the same list: filled by the first product (empty on entry), read by the
// next ones, which then cost a few flops per pair instead of a kernel evaluation. `shares`
// weight the coefficients when they are computed (kept coefficients hold the weights).

// u_t = sum_{pairs (s, n)} S^R(x_s + n L - x_t) f_s, one row per target.
PointField real_space_single_layer(const NeighborList& pairs, double xi, const PointField& forces,
                                   std::vector<double>* coefficients = nullptr,
                                   const PairShares* shares = nullptr);

// u_t,i = sum_{pairs (s, n)} T^R_ijk(x_s + n L - x_t) q_s,j n_s,k.
PointField real_space_double_layer(const NeighborList& pairs, double xi, const PointField& q,
                                   const PointField& normals, std::vector<double>* coefficients = nullptr,
                                   const PairShares* shares = nullptr);

}  // namespace rbcflow
