#pragma once
// Periodic single- and double-layer sums by Ewald splitting (section 5): real-space part over
// a neighbour list (section 5.3) plus smooth part by SPME (section 5.2), for fixed source and
// target positions. This is the workspace to keep for every product with the same geometry
// (FFT plans and influence function in the shared SpmeGrid; B-spline stencils, neighbour lists
// and work arrays here); only the densities change between products.
//
//   const EwaldChoice c = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-6, box, n);
//   auto grid = std::make_shared<const SpmeGrid>(box, c.parameters, FftPlanning::measure);
//   EwaldPlan plan(grid, sources, targets);   // once per geometry (time step)
//   PointField u = plan.single_layer(f);      // every GMRES iteration
//
// Normalisation (docs/references.md sections 1-2), densities with their quadrature weights:
//   single_layer: u(x_t) = sum_s G^per(x_s - x_t) f_s               (= 8 pi mu u),
//   double_layer: u_i(x_t) = sum_s T^per_ijk(x_s - x_t) q_s,j n_s,k,
// G^per and T^per the periodic kernels with the k = 0 mode removed; T^per is the periodic part
// of eq. (3), whose linear part is double_layer_linear_part().
//
// Coincident points: a target that is also a source (r = 0) gets that source's smooth term but
// not its singular real-space term, which the singular quadrature supplies. The single layer at
// such a target therefore depends on xi; adding ewald_real_stokeslet_self(xi) f_t gives the
// xi-independent regular part (the double layer needs nothing: lim T^R - T = 0).
//
// The real-space kernel coefficients of every pair are kept from the first product of each
// layer (real_space_sum.h; up to 2e8 pairs), so later products cost a few flops per pair.
// Products modify work arrays: one thread at a time per plan; each product is OpenMP-parallel.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "libsolver/common/memory_report.h"
#include "neighbor_list.h"
#include "libsolver/common/periodic_box.h"
#include "real_space_sum.h"
#include "spme_grid.h"
#include "spme_plan.h"

namespace rbcflow {

// Pair coefficients are kept for lists of at most this many pairs (16 bytes each: 3.2 GB). A
// bound of 5e7 dropped the cells' double-layer coefficients at 125 red cells (hematocrit 0.3):
// keeping them costs 0.8 GB there (peak 11.7 -> 12.5 GB, 94 -> 100 MB per cell) and saves
// 40% of the cell products (docs/performance.md, "Growth with the cell count").
inline constexpr std::int64_t kMaxKeptPairs = 200'000'000;

struct EwaldTimings {
  double real_space = 0.0;
  SpmeTimings smooth;
  double total() const {
    return real_space + smooth.spreading + smooth.fft + smooth.influence + smooth.interpolation;
  }
  EwaldTimings& operator+=(const EwaldTimings& o) {
    real_space += o.real_space;
    smooth.spreading += o.smooth.spreading;
    smooth.fft += o.smooth.fft;
    smooth.influence += o.smooth.influence;
    smooth.interpolation += o.smooth.interpolation;
    return *this;
  }
};

// The rows [begin, end) of a plan's sources whose real-space pairs one rank sums.
struct SourceRows {
  Eigen::Index begin = 0, end = 0;
};
// The rows [begin, end) of a plan's targets at which one rank sums the real-space pairs.
struct TargetRows {
  Eigen::Index begin = 0, end = 0;
};

class EwaldPlan {
 public:
  // `shares`: real-space pairs weighted 1 - share in both layers (real_space_sum.h).
  EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources,
            const PointField& targets, PairShares shares = {});
  // Targets are the sources.
  EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& points, PairShares shares = {});
  // One rank's part of the sums of the ranks that share a run: the real-space pairs of the
  // sources `rows` (numbered within them in `shares`), and the smooth part of every source in
  // this rank's slab of a distributed grid, else of the sources `rows` too. Products take every
  // source's density; the ranks' results sum to the whole. `sources` may be `targets` (the
  // stencils are then shared).
  EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources, const PointField& targets,
            SourceRows rows, PairShares shares = {});
  // The same split by targets: the real-space pairs at the targets `rows`, the smooth part on
  // this rank's slab of a distributed grid at every target, else at the targets `rows` too.
  // Products give every target's row (zero where this rank adds nothing).
  EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources, const PointField& targets,
            TargetRows rows);

  PointField single_layer(const PointField& forces);
  PointField double_layer(const PointField& q, const PointField& normals);
  // The smooth (SPME) part of single_layer alone, for a caller that holds the real-space part
  // as a matrix (wall/wall_real_space.h).
  PointField smooth_single_layer(const PointField& forces);
  // The same for forces = map x, through `spreading` = smooth().sources().spreading_matrix(map).
  PointField smooth_single_layer(const SpmeStencils::SpreadingMatrix& spreading, const PointField& x);

  // Keep the pair coefficients only for lists of at most n pairs (default kMaxKeptPairs; 0:
  // never), for a memory budget or a plan applied once.
  void keep_pairs_up_to(std::int64_t n) { max_kept_pairs_ = n; }
  // The smooth part's double layer transformed lean (SpmePlan::transform_lean), for a budget.
  void transform_lean(bool lean) { smooth_.transform_lean(lean); }
  // Throws std::logic_error after release_real_space().
  const NeighborList& neighbors() const;
  // Frees the neighbour list, for a caller that has assembled the real-space part itself
  // (wall/wall_real_space.h) and applies only the smooth part from now on; single_layer and
  // double_layer then throw std::logic_error.
  void release_real_space() { neighbors_.reset(); }
  // Adds "<prefix>: neighbour list", "kept pair coefficients", "B-spline stencils", "pair
  // shares", and its products' work arrays to the largest of all plans' (the grid itself is
  // the SpmeGridCache's).
  void report_memory(MemoryReport& report, const std::string& prefix) const;
  const SpmePlan& smooth() const { return smooth_; }
  // The source rows whose densities a product reads, ascending: all of them, or with
  // SourceRows those rows and, on a grid split over the ranks, the sources whose stencils reach
  // this rank's slab.
  std::vector<Eigen::Index> density_rows() const;
  double xi() const { return smooth_.grid().parameters().xi; }
  // Stage times of the last product.
  const EwaldTimings& timings() const { return timings_; }

 private:
  std::vector<double>* kept(std::vector<double>& coefficients) const;

  // The densities of the sources of the real-space sum and of the smooth part (in `copy` when
  // they are some rows of `density`).
  const PointField& real_space_rows(const PointField& density, PointField& copy) const;
  const PointField& smooth_rows(const PointField& density, PointField& copy) const;
  bool has_real_space_sources() const {
    return (!rows_ || rows_->end > rows_->begin) && (!target_rows_ || target_rows_->end > target_rows_->begin);
  }
  // Adds a result at the targets of the real-space sum (or of the smooth part) to `u`, a
  // result at every target.
  void add_at_rows(PointField& u, const PointField& at_rows) const;
  PointField smooth_at_every_target(PointField smooth) const;

  std::optional<SourceRows> rows_;         // the real-space sources of one rank, if not all
  bool smooth_of_rows_ = false;            // the smooth part's sources are rows_ too
  std::optional<TargetRows> target_rows_;  // the real-space targets of one rank, if not all
  Eigen::Index n_targets_ = 0;             // all of them
  bool smooth_at_rows_ = false;            // the smooth part's targets are target_rows_ too
  std::optional<NeighborList> neighbors_;  // empty after release_real_space()
  SpmePlan smooth_;
  PairShares shares_;
  std::vector<double> single_coefficients_, double_coefficients_;
  bool double_products_ = false;  // whether double_layer has run (for report_memory)
  std::int64_t max_kept_pairs_ = kMaxKeptPairs;
  EwaldTimings timings_;
};

}  // namespace rbcflow
