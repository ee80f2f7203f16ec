#pragma once
// Real-space parts of the Ewald sums (eq. 24 and 27) over the pairs of a NeighborList, r = 0
// pairs excluded (see neighbor_list.h). Parallel over targets (OpenMP).
#include <cstdint>
#include <vector>

#include "neighbor_list.h"
#include "libsolver/common/patch_node.h"
#include "libsolver/common/periodic_box.h"

namespace rbcflow {

// Pairs that count with weight 1 - share: the part of their integral that another rule supplies
// (the patches of the singular quadrature, where the regular rule's share is eta, the
// partition of unity: quadrature/singular_quadrature.h). Per caller's target t, the segments
// [offsets[t], offsets[t + 1]): node e of a segment is the caller's source first_source + e.node()
// with share e.eta(); a source may appear more than once (the shares add). The nodes are held by
// whoever built them, the singular corrections' folded nodes (operators/cell_layers.h), which
// must outlive the sums, or by `held` (from_lists). A pair is weighted at its nearest image
// only, which must lie within the cutoff and within half the shortest box side (else it is not
// weighted). Empty offsets: no weighted pair. Move-only: the segments may point into `held`.
struct PairShares {
  struct Segment {
    const PatchNode* nodes;
    std::int32_t count;
    std::int32_t first_source;
  };
  std::vector<std::int64_t> offsets;
  std::vector<Segment> segments;
  std::vector<PatchNode> held;

  PairShares() = default;
  PairShares(PairShares&&) = default;
  PairShares& operator=(PairShares&&) = default;
  PairShares(const PairShares&) = delete;
  PairShares& operator=(const PairShares&) = delete;
  // One segment per target over `held`: target t's sources and shares are entries
  // [offsets[t], offsets[t + 1]) of the lists.
  static PairShares from_lists(std::vector<std::int64_t> offsets, const std::vector<int>& sources,
                               const std::vector<float>& shares);
  std::size_t memory_bytes() const;  // what it holds itself: offsets, segments, held nodes
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
