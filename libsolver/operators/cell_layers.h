#pragma once
// The boundary-integral layers of eq. (4)-(5) over all cells, at the nodes of all cells, as
// matrix-free products for one fixed geometry (one time step):
//   single_layer(f)_t = integral_D G(x - x_t) f dS        (= 8 pi mu times a velocity)
//   double_layer(u)_t = p.v. integral_D T(x - x_t) u n dS  (periodic: with the linear part of (3))
// Free space: direct regular sums; periodic: SPME + real-space sums (EwaldPlan). In both, the
// singular self-interaction of each cell and the nearly-singular interaction of close cells
// (and of parts of one cell close to each other, near_targets.h) come from the quadrature
// corrections (libsolver/quadrature), built once in the constructor. Periodic: the regular
// rule's share of each patch (eta at the nodes within the real-space cutoff) comes out of the
// real-space Ewald sums, which weight those pairs by 1 - eta (PairShares), not out of the
// corrections.
// Node data are stacked cell by cell: row c * nodes_per_cell + p.
// On several ranks (LayerDomain::ranks) each rank builds the corrections of the cells it owns
// (a block of them: LayerDomain::owned_first, cell_owners.h) and sums only their nodes as
// sources; a product is the sum of the ranks' parts (Communicator::sum), the same on every rank.
// The cells it does not own it holds as nodes only (positions, normals, weights), and only
// those of its halo where the step names them (LayerDomain::held): its part is zero at every
// other cell's nodes and reads no density there (cell_halo.h). Products take and return every
// cell's rows, or, the held_ ones, the held cells' rows only (the layout of a step's densities:
// CellLayersAtPoints, stepper/halo_density.h).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "cell_halo.h"
#include "geometry/surface/cell_grids.h"
#include "libsolver/common/memory_report.h"
#include "libsolver/parallel/ownership.h"
#include "libsolver/quadrature/singular_quadrature.h"
#include "libsolver/spme/ewald_plan.h"
#include "libsolver/common/periodic_box.h"
#include "libsolver/spme/spme_grid_cache.h"

namespace rbcflow {

// Wall-clock seconds of the constructor's stages and of the corrections applied since (StepTimings).
struct CellLayersTimings {
  double geometry = 0.0;  // quadrature geometry of every cell and the Ewald plans
  double self = 0.0;      // singular corrections
  double near = 0.0;      // near-target search and nearly-singular corrections
  double applied = 0.0;   // the corrections applied in products so far (part of each product)
  EwaldTimings double_layer_ewald;  // the double layer's Ewald sums in products so far (this rank's)
};

// The cost model of the cells' double-layer Ewald sum (ewald_parameters.h). Its plan serves
// every GMRES product of (10) in a step (7-10 for lambda = 5), and the real-space coefficients
// of each pair are computed in the first product and read in the others (ewald_plan.h):
// measured on 13,824 random points in tube27's box (1 thread), 25-30 ns a pair to compute and
// 5 ns to read, so over a step's products about a fifth of computing them. The choice
// then moves to a larger cutoff and a coarser grid (tube27: cell products 3.9 -> 3.0 s per
// step), within the pairs a plan keeps.
// Without kept coefficients (max_kept_pairs = 0: a memory budget that cannot hold them), or
// where no choice within max_kept_pairs meets the tolerance (many cells: the pairs grow with
// the count at a fixed cutoff), every product computes them, and the choice is the default one.
RealSpaceUse double_layer_real_space(std::int64_t max_kept_pairs, double tolerance, const PeriodicBox& box,
                                     long nodes);

// Brings the rows a rank reads of a step's single-layer density that it does not hold: an
// operator built for the density (single_layer_density below, CellLayersAtPoints) calls it with
// its halo (cell positions in the layers' order, ascending) once it has found it, before it
// reads the density; the owned cells' rows must be there already. Collective: every rank's
// operator calls it at the same point. Empty: the density is whole on every rank.
using DensityHalo = std::function<void(const std::vector<int>& halo)>;

// The cells a rank holds in a step's layers besides its own: the step's halo (ascending
// positions in the layers' order: cell_layers_halo, which must hold the layers' own halo) and
// every cell's sphere.
struct HeldCells {
  std::vector<int> halo;
  std::vector<CellSphere> spheres;
};

struct LayerDomain {
  std::optional<PeriodicBox> box;  // empty: free space
  double ewald_tolerance = 1e-6;
  std::int64_t max_kept_pairs = kMaxKeptPairs;  // the Ewald plans' bound (ewald_plan.h)
  bool lean_transforms = false;  // the double layer's density a component at a time (SpmePlan::transform_lean)
  Communicator ranks{};  // the ranks that share the products (default: one)
  // The cells' owners (cell_owners.h): rank r owns cells owned_first[r] .. owned_first[r + 1] - 1
  // (ranks + 1 entries, from 0 to the number of cells); empty: owned_block's.
  std::vector<int> owned_first{};
  // The cells besides the owned block whose nodes the layers hold, with every cell's sphere
  // (cell_sphere, in the layers' order) from which their halo is taken; empty: every cell's
  // nodes, and the spheres from them.
  std::optional<HeldCells> held{};
};

// The grid of a periodic domain's products of `nodes` cell nodes: the double layer's
// (with_double_layer) or the single layer's, from `grid_cache` (null: built afresh). Collective.
std::shared_ptr<const SpmeGrid> cell_layer_grid(const LayerDomain& domain, long nodes, bool with_double_layer,
                                                SpmeGridCache* grid_cache);

// The halo CellLayers::halo_with(other_slabs) names for these cells (positions in the layers'
// order, ascending), from their spheres in that order (cell_sphere), before the layers are
// built: the cells a rank reads or adds to in a step besides its own (domain.owned_first's
// block). Collective, as the layers (their grids).
std::vector<int> cell_layers_halo(const std::vector<CellSphere>& spheres, const CellGrids& grids,
                                  const LayerDomain& domain, const QuadratureOptions& options,
                                  bool with_double_layer, SpmeGridCache* grid_cache,
                                  const std::vector<SlabPlanes>& other_slabs);

class CellLayers {
 public:
  // with_double_layer = false skips everything the double layer needs (lambda = 1). SPME grids
  // come from `grid_cache` when given (kept across steps; it must outlive this object).
  // single_layer_density (at the held rows, held_cells()'s nodes x 3: every cell's where every
  // cell is held), when given: the single layer of that density, the
  // only one a time step needs (its traction, in every sweep of the step), is computed here,
  // each cell's single-layer corrections applied as soon as they are built and freed, and the
  // single-layer Ewald plan freed after its one product: kept, they were a third of a step's
  // memory. single_layer(f) and single_layer_part(f) then return it, for that density only: the
  // same matrix, which is read only here (the caller keeps it while this is built; no copy of a
  // vector of every node is held after). `bring_density` is called with halo() before it is read.
  CellLayers(const std::vector<SHCoeffs>& cells, std::shared_ptr<const CellGrids> grids,
             const LayerDomain& domain, const QuadratureOptions& options = {}, bool with_double_layer = true,
             SpmeGridCache* grid_cache = nullptr, const Eigen::MatrixXd* single_layer_density = nullptr,
             const DensityHalo& bring_density = {});
  ~CellLayers();

  int num_cells() const { return num_cells_; }
  int nodes_per_cell() const { return grids_->n_grid->grid().size(); }
  // The cells whose nodes this rank holds (the owned and the held halo, or every cell), ascending.
  const std::vector<int>& held_cells() const { return held_; }
  bool holds_all() const { return static_cast<int>(held_.size()) == num_cells_; }
  // The held cells' nodes, stacked in held_cells()'s order (every cell's on one rank).
  const SourceNodes& nodes() const { return nodes_; }
  // The owned block's rows of nodes() (contiguous: the held cells are ascending).
  SourceRows owned_nodes() const;
  // The first row of held cell c in nodes() (c held).
  Eigen::Index held_row(int c) const { return static_cast<Eigen::Index>(held_position_[c]) * nodes_per_cell(); }
  // Rows of every cell (stacked in the layers' order) at the held cells' rows of nodes(), and
  // back (zero at the cells not held).
  Eigen::MatrixXd held_rows(const Eigen::MatrixXd& stacked) const;
  Eigen::MatrixXd every_rows(Eigen::MatrixXd held) const;
  // `stacked` (every cell's rows) at the held rows: itself where every cell is held, else
  // gathered into `gathered`.
  const Eigen::MatrixXd& at_held(const Eigen::MatrixXd& stacked, Eigen::MatrixXd& gathered) const;
  // The cells whose corrections this rank builds; only they have a quadrature geometry.
  const OwnedRange& owned() const { return owned_; }
  std::vector<int> owned_first() const;  // every rank's first owned cell, and the number of cells
  const CellQuadratureGeometry& cell(int c) const { return *cells_[c]; }
  const std::shared_ptr<const CellQuadratureGeometry>& cell_geometry(int c) const { return cells_[c]; }
  const LayerDomain& domain() const { return domain_; }
  SpmeGridCache* grid_cache() const { return grid_cache_; }
  bool has_double_layer() const { return with_double_layer_; }
  int near_targets() const;  // nearly-singular (target, source cell) pairs, of all ranks
  const CellLayersTimings& build_timings() const { return timings_; }
  // What the step's cell operator holds on this rank (common/memory_report.h): "the held
  // cells' nodes", "cell geometry" (the owned and halo cells'), "self corrections: ...",
  // "near corrections: ...", "cell Ewald single/double: ...".
  void report_memory(MemoryReport& report) const;

  // Every cell's rows of f, or, where the layers were built for a single-layer density, that
  // density itself (held rows): std::logic_error for another matrix.
  Eigen::MatrixXd single_layer(const Eigen::MatrixXd& f);
  // This rank's part of single_layer(f), at every node: its cells' corrections and nodes as
  // sources, its slab of the grid; zero at the nodes beyond the real-space cutoff and the near
  // distance of its cells and off its slab. single_layer(f) is the sum of the ranks' parts.
  Eigen::MatrixXd single_layer_part(const Eigen::MatrixXd& f);
  Eigen::MatrixXd double_layer(const Eigen::MatrixXd& u);
  // This rank's part of double_layer(u), at every node: its cells' corrections and nodes as
  // sources, its slab of the grid. double_layer(u) is the sum of the ranks' parts; a caller
  // that needs only some rows of it sums the parts itself (parallel/owned_rows.h). With
  // `uniform` (periodic), the part's one term that is the same at every node, the linear part of
  // (3) of its sources, is returned there instead of added to every row: the part is then zero
  // at the nodes beyond the real-space cutoff and the near distance of its cells and off its slab.
  Eigen::MatrixXd double_layer_part(const Eigen::MatrixXd& u, Eigen::RowVector3d* uniform = nullptr);
  // double_layer_part of a density given at the held rows (nodes()'s order), at the held rows:
  // no vector of every cell's rows on the way (GMRES's products, cell_velocity.h).
  Eigen::MatrixXd held_double_layer_part(const Eigen::MatrixXd& u_held, Eigen::RowVector3d* uniform = nullptr);
  // single_layer_part at the held rows, of a density at the held rows (the constructor's, if
  // one was given: std::logic_error for another matrix).
  Eigen::MatrixXd held_single_layer_part(const Eigen::MatrixXd& f_held);
  // The rows of u that double_layer_part reads, ascending: its cells' and, on a grid split over
  // the ranks, the nodes whose B-spline stencils reach its slab (all rows on one rank).
  std::vector<int> density_rows() const;
  // The cells this rank does not own at whose rows its parts of products can be nonzero and
  // whose rows it reads (cell_halo.h), ascending: on a grid split over the ranks, the cells
  // within the real-space cutoff and the near distance of its cells and those reaching its slab
  // of a grid; elsewhere every cell it does not own (none on one rank).
  const std::vector<int>& halo() const { return halo_; }
  // The halo of a step that also uses other operators with the cells (the cells' layers at the
  // wall, the wall's velocity at the cells): halo() and the cells whose B-spline stencils can
  // reach `other_slabs`, this rank's planes of those operators' grids split over the ranks.
  std::vector<int> halo_with(const std::vector<SlabPlanes>& other_slabs) const;

 private:
  struct NearCorrection {
    std::unique_ptr<LayerCorrection> single, double_;
    std::vector<int> rows;  // stacked target rows
  };
  // Below, node data are the held cells' rows (nodes()'s order).
  Eigen::MatrixXd apply_corrections(Layer layer, const Eigen::MatrixXd& density);
  // The regular sums (SPME + real space, or direct in free space) of the owned cells' nodes
  // as sources, at every held node: this rank's part.
  Eigen::MatrixXd regular_single_layer(const Eigen::MatrixXd& f);
  Eigen::MatrixXd regular_double_layer(const Eigen::MatrixXd& u, Eigen::RowVector3d* uniform = nullptr);
  // The owned cells' rows of held node data.
  template <class Matrix>
  auto owned_rows(const Matrix& held) const {
    return held.middleRows(owned_nodes().begin, owned_.size() * nodes_per_cell());
  }
  bool owns_all() const { return owned_.size() == num_cells(); }
  // The patch nodes the layer's corrections left to the real-space sum, by target row, as
  // segments of the corrections' folded nodes (which therefore live as long as the plans).
  PairShares take_folded_shares(Layer layer) const;
  Eigen::MatrixXd cell_block(const Eigen::MatrixXd& held, int c) const;

  std::shared_ptr<const CellGrids> grids_;
  LayerDomain domain_;
  SpmeGridCache* grid_cache_;
  OwnedRange owned_;
  std::vector<int> held_;           // held_cells()
  std::vector<int> held_position_;  // of each cell in held_, or -1
  std::vector<CellSphere> spheres_;  // every cell's (LayerDomain::held), or empty: from the nodes
  std::vector<int> halo_;
  HaloExtent halo_extent_;  // what the halo is taken from (halo_with)
  int num_cells_ = 0;
  std::vector<std::shared_ptr<const CellQuadratureGeometry>> cells_;  // null where not owned
  SourceNodes nodes_;  // of the held cells
  std::vector<std::unique_ptr<LayerCorrection>> self_single_, self_double_;
  std::vector<NearCorrection> near_;  // per source cell
  std::unique_ptr<EwaldPlan> single_plan_, double_plan_;
  // With a single_layer_density: that density (read only while this is built, then only its
  // address compared) and this rank's part of its single layer at the held rows (the
  // corrections and the single-layer plan above are then empty).
  const Eigen::MatrixXd* single_density_ = nullptr;
  std::optional<Eigen::MatrixXd> single_part_;
  bool with_double_layer_ = true;
  CellLayersTimings timings_;
};

}  // namespace rbcflow
