#pragma once
// The wall single layer of eq. (7)/(9), matrix-free: for nodal force densities f on the wall's
// linear elements,  (N_W f)(x_t) = int_W G(y - x_t) f(y) dS(y)  (= 8 pi mu u)  at fixed targets.
// Gauss-7 sum over all triangles (direct in free space; EwaldPlan with the periodic G^per in a
// box) plus the sparse near-field correction (near_field.h), built once: the wall does not move.
// A target at a Gauss point (a centroid; snapped onto it) skips that point's G(0); in a box it gets the regular
// part of G^per - G there, the smooth term plus ewald_real_stokeslet_self (ewald_plan.h).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>

#include "libsolver/parallel/communicator.h"
#include "libsolver/parallel/owned_rows.h"
#include "libsolver/spme/ewald_plan.h"
#include "libsolver/common/periodic_box.h"
#include "libsolver/spme/spme_grid_cache.h"
#include "near_field.h"
#include "symmetric_block_matrix.h"
#include "wall_elements.h"
#include "wall_real_space.h"

namespace rbcflow {

// The assembled near field and real-space part (RealSpace::assembled) keep single-precision
// entries for a tolerance of at least this. Rounded, an entry moves by at most 2^-24 (6e-8) of
// itself, so a product by at most 6e-8 of the sum of its terms' magnitudes, a 16th of this
// tolerance; a small tube's products move by 2-3e-8 of their size (test_symmetric_block_matrix),
// within the tenth of the tolerance the assembled part is built for (kAssembledToleranceFactor).
// It halves the largest structure of the wall solve (1.06 of the 16 MB a cell holds at a
// thousand cells) and what its products read.
inline constexpr double kSingleBlocksTolerance = 1e-6;

class WallOperator {
 public:
  // Free space (direct O(targets x Gauss points) sums; for tests and small walls).
  WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets);
  // Periodic box; the Ewald parameters are chosen for `ewald_tolerance` (ewald_parameters.h),
  // the grid taken from `grid_cache` when given (spme_grid_cache.h). `real_space` says whether
  // the real-space sum is evaluated at every product or assembled once as a sparse matrix (for
  // an operator applied many times, the wall solve; the choice then favours a large cutoff and a coarse grid, at a tenth of the tolerance:
  // kAssembledRealSpace and kAssembledToleranceFactor in wall_real_space.h).
  // `chosen_for_targets` > 0: the parameters are those of that many targets, the whole set of
  // which `targets` is one rank's share (the same grid on every rank and as on one).
  // `ranks` (RealSpace::assembled): each rank assembles the rows of its block of the targets
  // and a product adds the ranks' rows; the smooth part is computed on the ranks' slabs of the
  // grid (spme_grid.h) and added in the same sum, or, in a build without FFTW's MPI library,
  // on every rank whole (the product then has the same bits as on one rank).
  // `assembled_use` (RealSpace::assembled): the cost model's weight of a pair and the bound on
  // the pairs the matrix holds; any bound meets the tolerance, a cutoff inside the near field's
  // reach included. The assembled blocks keep their entries in single precision when
  // `ewald_tolerance` is at least kSingleBlocksTolerance.
  // `rows` (RealSpace::assembled): which rank assembles which targets' rows, over `ranks`;
  // default the blocks of the targets in their order (owned_block). The wall solve passes the
  // segments of its preconditioner's slabs (wall_node_segments, wall_preconditioner.h); with
  // them given on more than one rank, each rank computes the near field at its rows only
  // (near_at_rows_only()), which is all its assembled rows and preconditioner blocks read.
  enum class RealSpace { per_product, assembled };
  WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets,
               const PeriodicBox& box, double ewald_tolerance, SpmeGridCache* grid_cache = nullptr,
               RealSpace real_space = RealSpace::per_product, long chosen_for_targets = 0,
               Communicator ranks = {}, const RealSpaceUse& assembled_use = kAssembledRealSpace,
               std::optional<OwnedSegments> rows = std::nullopt);


  // One rank's part of the operator at every target of a run's ranks (the cells' nodes): the
  // near field and real-space sum at its `rows` of the targets, the smooth part at every
  // target on its slab of the grid (chosen for all the targets; split over `ranks` where the
  // build can, else at its rows only). Products give every target's row; the ranks' sum is the
  // whole operator's product. Each product computes its real-space pairs (none are kept: a
  // step applies it once). `all_targets` (0: the targets' rows), the count the grid is chosen
  // for, where `targets` are only those this rank's part can reach (the held cells' nodes,
  // cell_layers.h).
  WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets, TargetRows rows,
               const PeriodicBox& box, double ewald_tolerance, SpmeGridCache* grid_cache, Communicator ranks,
               long all_targets = 0);
  // The grid that constructor takes for `wall_points` wall nodes at `targets` targets: known
  // before the operator is built (the slabs of a step's halo). Collective, as the constructor.
  static std::shared_ptr<const SpmeGrid> grid_at_rows(SpmeGridCache* grid_cache, double ewald_tolerance,
                                                      const PeriodicBox& box, long wall_points, long targets,
                                                      const Communicator& ranks);

  // N_W f at the targets, one row each; f one row per wall node.
  PointField apply(const PointField& f);
  // This rank's segment (segments()) of apply(f) (as to_vector, parallel/owned_rows.h): for an
  // operator at the wall nodes with assembled rows (the wall solve's GMRES on split vectors),
  // the ranks' parts are summed only where the smooth part is split over them, and only into
  // each owner's segment. Without assembled rows: the segment of apply(f).
  Eigen::VectorXd apply_mine(const PointField& f);
  // The nodes of f that apply_mine reads, ascending: with assembled rows, those of its rows'
  // blocks, those whose Gauss points its slab of the grid spreads (every node on a whole grid)
  // and, on the rank that adds them, the coincident pairs' triangles'; else every node.
  std::vector<int> density_nodes() const;
  const Communicator& ranks() const { return ranks_; }
  // The smooth part's grid (periodic box only): a rank's part at targets (TargetRows) is nonzero
  // at its rows and at the targets whose stencils reach its slab of a grid split over the ranks.
  const SpmeGrid& grid() const;
  // The targets split over the ranks: the assembled rows' segments, else blocks of the targets.
  const OwnedSegments& segments() const { return segments_; }

  const WallElements& elements() const { return *elements_; }
  // With RealSpace::assembled the correction is part of the assembled rows and empty here.
  const NearField& near() const { return near_; }
  // Whether near() holds only the rows of this rank's segment (the other targets' are empty).
  bool near_at_rows_only() const { return near_at_rows_only_; }
  // Frees near().local, for the wall solver once it holds its factorisation.
  void release_local_near_field() { near_.local = Eigen::SparseMatrix<double>(); }
  const PointField& targets() const { return targets_; }
  int num_targets() const { return static_cast<int>(targets_.rows()); }
  // "<prefix>: near field", "<prefix>: assembled real space", "<prefix> Ewald: ..." (memory_report.h).
  void report_memory(MemoryReport& report, const std::string& prefix) const;

 private:
  // The near field at the targets `rows` selects (all when empty; near_field.h).
  WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets,
               const std::function<bool(int)>& rows);

  std::shared_ptr<const WallElements> elements_;
  PointField targets_;
  NearField near_;                    // at the targets, or at target_rows_ of them
  std::optional<TargetRows> target_rows_;
  std::optional<EwaldPlan> ewald_;
  // Periodic box, RealSpace::assembled: the real-space part of the Ewald sum as a sparse matrix
  // (wall_real_space.h) plus the near-field correction, for an operator applied many times at
  // fixed targets (the wall solve). Products change by rounding only.
  std::optional<SymmetricBlockMatrix> near_and_real_;  // this rank's rows
  Communicator ranks_;
  OwnedSegments segments_;
  bool near_at_rows_only_ = false;
  // ... and the SPME spreading of the Gauss points' densities as one matrix on the nodal
  // densities (SpmeStencils::spreading_matrix of WallElements::density_map).
  std::optional<SpmeStencils::SpreadingMatrix> node_spreading_;
};

}  // namespace rbcflow
