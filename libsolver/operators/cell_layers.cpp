#include "cell_layers.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <tuple>

#include "libsolver/spme/double_layer_linear.h"
#include "libsolver/spme/real_space_sum.h"
#include "near_targets.h"
#include "libsolver/common/scoped_timer.h"

namespace rbcflow {

RealSpaceUse double_layer_real_space(std::int64_t max_kept_pairs, double tolerance, const PeriodicBox& box,
                                     long nodes) {
  if (max_kept_pairs <= 0) return {};
  const RealSpaceUse kept{0.2, static_cast<double>(max_kept_pairs)};
  try {
    choose_ewald_parameters(EwaldKernel::stresslet, tolerance, box, nodes, nodes, kept);
    return kept;
  } catch (const std::invalid_argument&) {  // no choice within the kept pairs; a bad tolerance
    return {};                              // is refused by the default choice in turn
  }
}

std::shared_ptr<const SpmeGrid> cell_layer_grid(const LayerDomain& domain, long nodes, bool with_double_layer,
                                                SpmeGridCache* grid_cache) {
  if (!domain.box) throw std::invalid_argument("cell_layer_grid: free space has no grid");
  const PeriodicBox& box = *domain.box;
  if (!with_double_layer)
    return ewald_grid(grid_cache, EwaldKernel::stokeslet, domain.ewald_tolerance, box, nodes, -1, {}, domain.ranks);
  return ewald_grid(grid_cache, EwaldKernel::stresslet, domain.ewald_tolerance, box, nodes, -1,
                    double_layer_real_space(domain.max_kept_pairs, domain.ewald_tolerance, box, nodes), domain.ranks);
}

namespace {

// This rank's cells: its block of LayerDomain::owned_first, or owned_block's.
OwnedRange owned_cells(int cells, const LayerDomain& domain) {
  const std::vector<int>& first = domain.owned_first;
  if (first.empty()) return owned_block(cells, domain.ranks);
  const std::size_t p = static_cast<std::size_t>(domain.ranks.size());
  bool valid = first.size() == p + 1 && first.front() == 0 && first.back() == cells;
  for (std::size_t r = 0; valid && r < p; ++r) valid = first[r] <= first[r + 1];
  if (!valid) throw std::invalid_argument("CellLayers: owned_first must rise from 0 to the number of cells, one entry a rank and one more");
  const int r = domain.ranks.rank();
  return {first[static_cast<std::size_t>(r)], first[static_cast<std::size_t>(r) + 1]};
}

// The cells whose nodes the layers hold: the owned block and domain.held's halo, or every cell.
std::vector<int> cells_held(int cells, OwnedRange owned, const LayerDomain& domain) {
  std::vector<int> held;
  if (!domain.held) {
    held.resize(static_cast<std::size_t>(cells));
    std::iota(held.begin(), held.end(), 0);
    return held;
  }
  const std::vector<int>& halo = domain.held->halo;
  if (domain.held->spheres.size() != static_cast<std::size_t>(cells))
    throw std::invalid_argument("CellLayers: LayerDomain::held needs one sphere a cell");
  for (std::size_t k = 0; k < halo.size(); ++k)
    if (halo[k] < 0 || halo[k] >= cells || owned.contains(halo[k]) || (k > 0 && halo[k] <= halo[k - 1]))
      throw std::invalid_argument("CellLayers: LayerDomain::held's halo must be ascending cells not owned");
  held = halo;
  for (int c = owned.begin; c < owned.end; ++c) held.push_back(c);
  std::sort(held.begin(), held.end());
  return held;
}

}  // namespace

std::vector<int> CellLayers::owned_first() const {
  if (!domain_.owned_first.empty()) return domain_.owned_first;
  std::vector<int> first;
  for (int r = 0; r < domain_.ranks.size(); ++r) first.push_back(owned_block(num_cells_, r, domain_.ranks.size()).begin);
  first.push_back(num_cells_);
  return first;
}

CellLayers::CellLayers(const std::vector<SHCoeffs>& cells, std::shared_ptr<const CellGrids> grids,
                       const LayerDomain& domain, const QuadratureOptions& options, bool with_double_layer,
                       SpmeGridCache* grid_cache, const Eigen::MatrixXd* single_layer_density,
                       const DensityHalo& bring_density)
    : grids_(std::move(grids)),
      domain_(domain),
      grid_cache_(grid_cache),
      owned_(owned_cells(static_cast<int>(cells.size()), domain)),
      held_(cells_held(static_cast<int>(cells.size()), owned_, domain)),
      num_cells_(static_cast<int>(cells.size())),
      with_double_layer_(with_double_layer) {
  if (cells.empty()) throw std::invalid_argument("CellLayers: no cells");
  if (single_layer_density) {
    if (single_layer_density->rows() != static_cast<Eigen::Index>(held_.size()) * nodes_per_cell() ||
        single_layer_density->cols() != 3)
      throw std::invalid_argument("CellLayers: the single-layer density must be (held nodes x 3)");
    single_density_ = single_layer_density;
  }
  ScopedTimer geometry_timer(timings_.geometry);
  const int nc = num_cells_, np = nodes_per_cell(), nh = static_cast<int>(held_.size());
  if (domain_.held) spheres_ = domain_.held->spheres;
  held_position_.assign(static_cast<std::size_t>(nc), -1);
  for (int k = 0; k < nh; ++k) held_position_[held_[k]] = k;
  // Only the held cells' shapes are read.
  cells_.resize(nc);
  std::vector<SourceNodes> not_owned(nh);
#pragma omp parallel for schedule(dynamic)
  for (int k = 0; k < nh; ++k) {
    const int c = held_[k];
    if (owned_.contains(c)) {
      cells_[c] = std::make_shared<const CellQuadratureGeometry>(cells[c], grids_, options);
    } else {
      not_owned[k] = cell_nodes(cells[c], *grids_);
    }
  }
  nodes_.x.resize(nh * np, 3);
  nodes_.normal.resize(nh * np, 3);
  nodes_.weight.resize(nh * np);
  for (int k = 0; k < nh; ++k) {
    const int c = held_[k];
    const SourceNodes& n = cells_[c] ? cells_[c]->nodes() : not_owned[k];
    nodes_.x.middleRows(k * np, np) = n.x;
    nodes_.normal.middleRows(k * np, np) = n.normal;
    nodes_.weight.segment(k * np, np) = n.weight;
  }
  // The Ewald grids first: the corrections need their xi, and leave the patch nodes within
  // the real-space cutoff (their nearest images) to the real-space sums, which weight those
  // pairs by 1 - eta (PairShares) instead of the corrections removing eta K w; the nodes beyond
  // the cutoff are in no real-space sum, and have no share to remove (NodeShares). The grids
  // are chosen for all the cells' nodes, on every rank alike.
  std::shared_ptr<const SpmeGrid> single_grid, double_grid;
  double xi_single = 0.0, xi_double = 0.0;
  std::array<NodeShares, 2> node_shares{};
  if (domain_.box) {
    const PeriodicBox& box = *domain_.box;
    single_grid = cell_layer_grid(domain_, nc * np, false, grid_cache_);
    xi_single = single_grid->parameters().xi;
    node_shares[0] = {pair_share_radius(box, single_grid->parameters().cutoff), single_grid->parameters().cutoff};
    if (with_double_layer) {
      double_grid = cell_layer_grid(domain_, nc * np, true, grid_cache_);
      xi_double = double_grid->parameters().xi;
      node_shares[1] = {pair_share_radius(box, double_grid->parameters().cutoff), double_grid->parameters().cutoff};
    }
  }
  // A nearly-singular target lies within the near distance of the continuous surface, which
  // between the nodes can reach beyond their bounding sphere (cell_halo.h's spheres), by less
  // than the mesh size h (test_cell_halo.cpp): the reach adds h.
  double near_reach = 0.0;
  for (int c = owned_.begin; c < owned_.end; ++c)
    near_reach = std::max(near_reach, cells_[c]->near_distance() + cells_[c]->mesh_size());
  halo_extent_ = layers_halo_extent(near_reach, single_grid.get(), double_grid.get());
  halo_ = halo_with({});
  if (!std::includes(held_.begin(), held_.end(), halo_.begin(), halo_.end()))
    throw std::logic_error("CellLayers: the held cells (LayerDomain::held) do not hold the layers' halo");
  geometry_timer.stop();
  if (single_density_ && bring_density) bring_density(halo_);
  const Eigen::MatrixXd* single_held = single_density_;  // at the held rows, read in the build only
  // The single layer of a given density is applied once, as its corrections are built: they
  // remove their patch nodes' shares themselves (node entries, freed with the correction) instead
  // of folding them into the plan's pair shares, which would be held through every cell's
  // build (8 bytes a folded node, as many as the double layer's).
  if (single_density_) node_shares[0].fold = 0.0;
  self_single_.resize(nc);
  self_double_.resize(nc);
  near_.resize(nc);
  // With a single-layer density, each single-layer correction is applied as it is built and
  // freed: the self rows of a cell and the rows of its near targets, added up after the loops.
  Eigen::MatrixXd single_corrections;
  std::vector<Eigen::MatrixXd> near_single(nc);
  const auto apply_now = [&](int c, std::unique_ptr<LayerCorrection>& correction) {
    const Eigen::MatrixXd block = cell_block(*single_held, c);
    Eigen::MatrixXd out = correction->apply(block, cells_[c]->patch_data(block));
    correction.reset();
    return out;
  };
  if (single_density_) single_corrections = Eigen::MatrixXd::Zero(nodes_.size(), 3);
  std::optional<Eigen::MatrixXd> single_regular;  // the regular (Ewald) part of the single layer
  ScopedTimer self_timer(timings_.self);
#pragma omp parallel for schedule(dynamic)
  for (int c = owned_.begin; c < owned_.end; ++c) {
    const auto targets = cells_[c]->node_targets();
    if (with_double_layer) {
      std::tie(self_single_[c], self_double_[c]) =
          LayerCorrection::single_and_double(cells_[c], xi_single, xi_double, targets, node_shares);
    } else {
      self_single_[c] = std::make_unique<LayerCorrection>(cells_[c], LayerKernel{Layer::single, xi_single}, targets,
                                                          node_shares[0]);
    }
    if (single_density_) single_corrections.middleRows(held_row(c), np) = apply_now(c, self_single_[c]);
  }
  self_timer.stop();
  ScopedTimer near_timer(timings_.near);
#pragma omp parallel for schedule(dynamic)
  for (int c = owned_.begin; c < owned_.end; ++c) {
    // Nodes of other cells closer than the near distance (nearest periodic image), and the
    // cell's own nodes near another part of its surface.
    const int row = static_cast<int>(held_row(c));
    NearTargets near = find_near_targets(*cells_[c], nodes_.x, domain_.box, row, row + np);
    NearTargets self = find_self_near_targets(*cells_[c], row);
    near.targets.insert(near.targets.end(), self.targets.begin(), self.targets.end());
    near.rows.insert(near.rows.end(), self.rows.begin(), self.rows.end());
    near_[c].rows = std::move(near.rows);
    const std::vector<QuadratureTarget>& near_targets = near.targets;
    if (near_targets.empty()) continue;
    if (with_double_layer) {
      std::tie(near_[c].single, near_[c].double_) =
          LayerCorrection::single_and_double(cells_[c], xi_single, xi_double, near_targets, node_shares);
    } else {
      near_[c].single = std::make_unique<LayerCorrection>(cells_[c], LayerKernel{Layer::single, xi_single},
                                                          near_targets, node_shares[0]);
    }
    if (single_density_) near_single[c] = apply_now(c, near_[c].single);
  }
  near_timer.stop();
  if (single_density_) {
    for (int c = owned_.begin; c < owned_.end; ++c)
      for (std::size_t k = 0; k < near_[c].rows.size(); ++k) single_corrections.row(near_[c].rows[k]) += near_single[c].row(k);
  }
  // A rank without cells takes part in the transforms of a grid split over the ranks.
  if (domain_.box && (!owned_.empty() || single_grid->distributed())) {
    ScopedTimer plans_timer(timings_.geometry);
    // One rank: the nodes are sources and targets (the stencils shared); several: the owned
    // cells' nodes are the real-space sources, every held node a target (ewald_plan.h).
    auto plan = [&](std::shared_ptr<const SpmeGrid> grid, Layer layer) {
      const SourceRows rows = owned_nodes();
      // The single layer of a given density folded nothing (its corrections are gone).
      PairShares shares = layer == Layer::single && single_density_ ? PairShares{} : take_folded_shares(layer);
      return owns_all() ? std::make_unique<EwaldPlan>(std::move(grid), nodes_.x, std::move(shares))
                        : std::make_unique<EwaldPlan>(std::move(grid), nodes_.x, nodes_.x, rows, std::move(shares));
    };
    // Each plan takes its layer's folded nodes as its pair shares. The step's single layer is
    // computed and its plan freed before the double layer's plan is built, so that the two
    // plans, their lists and shares never live together.
    single_plan_ = plan(single_grid, Layer::single);
    // Applied once when the single layer is computed here: nothing to keep.
    single_plan_->keep_pairs_up_to(single_density_ ? 0 : domain_.max_kept_pairs);
    plans_timer.stop();
    if (single_density_) {
      single_regular = regular_single_layer(*single_held);
      single_plan_.reset();
    }
    if (with_double_layer) {
      ScopedTimer double_timer(timings_.geometry);
      double_plan_ = plan(double_grid, Layer::double_);
      double_plan_->keep_pairs_up_to(domain_.max_kept_pairs);
      double_plan_->transform_lean(domain_.lean_transforms);
    }
  }
  if (single_density_) {
    if (!single_regular) single_regular = regular_single_layer(*single_held);  // free space, or no plan here
    single_part_ = *single_regular + single_corrections;
    single_plan_.reset();
  }
}

namespace {

// Row t's source in the owned block [first, first + n) that coincides with it, or -1.
std::vector<int> coincident_sources(int targets, int first, int n) {
  std::vector<int> self(targets, -1);
  for (int s = 0; s < n; ++s) self[first + s] = s;
  return self;
}

}  // namespace

SourceRows CellLayers::owned_nodes() const {
  if (owned_.empty()) return {};
  const Eigen::Index first = held_row(owned_.begin);
  return {first, first + static_cast<Eigen::Index>(owned_.size()) * nodes_per_cell()};
}

Eigen::MatrixXd CellLayers::held_rows(const Eigen::MatrixXd& stacked) const {
  const int np = nodes_per_cell();
  if (stacked.rows() != static_cast<Eigen::Index>(num_cells_) * np)
    throw std::invalid_argument("CellLayers::held_rows: not one row a node of every cell");
  Eigen::MatrixXd held(static_cast<Eigen::Index>(held_.size()) * np, stacked.cols());
  for (std::size_t k = 0; k < held_.size(); ++k)
    held.middleRows(static_cast<Eigen::Index>(k) * np, np) = stacked.middleRows(static_cast<Eigen::Index>(held_[k]) * np, np);
  return held;
}

Eigen::MatrixXd CellLayers::every_rows(Eigen::MatrixXd held) const {
  if (held.rows() != nodes_.size()) throw std::invalid_argument("CellLayers::every_rows: not one row a held node");
  if (holds_all()) return held;
  const int np = nodes_per_cell();
  Eigen::MatrixXd every = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(num_cells_) * np, held.cols());
  for (std::size_t k = 0; k < held_.size(); ++k)
    every.middleRows(static_cast<Eigen::Index>(held_[k]) * np, np) = held.middleRows(static_cast<Eigen::Index>(k) * np, np);
  return every;
}

const Eigen::MatrixXd& CellLayers::at_held(const Eigen::MatrixXd& stacked, Eigen::MatrixXd& gathered) const {
  if (holds_all()) return stacked;
  gathered = held_rows(stacked);
  return gathered;
}

Eigen::MatrixXd CellLayers::regular_single_layer(const Eigen::MatrixXd& f) {
  const int first = static_cast<int>(owned_nodes().begin), n = owned_.size() * nodes_per_cell();
  if (domain_.box) {
    if (!single_plan_) return Eigen::MatrixXd::Zero(nodes_.size(), 3);  // no cell owned here
    const PointField weighted = f.array().colwise() * nodes_.weight.array();
    return single_plan_->single_layer(weighted);
  }
  const SourceNodes sources{owned_rows(nodes_.x), owned_rows(nodes_.weight), owned_rows(nodes_.normal)};
  return regular_layer_sum(sources, owned_rows(f), LayerKernel{Layer::single, 0.0}, nodes_.x,
                           coincident_sources(nodes_.size(), first, n));
}

Eigen::MatrixXd CellLayers::regular_double_layer(const Eigen::MatrixXd& u, Eigen::RowVector3d* uniform) {
  const int first = static_cast<int>(owned_nodes().begin), n = owned_.size() * nodes_per_cell();
  if (domain_.box) {
    if (uniform) uniform->setZero();
    if (!double_plan_) return Eigen::MatrixXd::Zero(nodes_.size(), 3);
    const PointField q = u.array().colwise() * nodes_.weight.array();
    Eigen::MatrixXd regular = double_plan_->double_layer(q, nodes_.normal);
    timings_.double_layer_ewald += double_plan_->timings();
    const PointField owned_q = owned_rows(q), owned_normals = owned_rows(nodes_.normal);
    const Eigen::RowVector3d linear =
        double_layer_linear_part(*domain_.box, owned_rows(nodes_.x), owned_q, owned_normals, nodes_per_cell());
    if (uniform) {
      *uniform = linear;
    } else {
      regular.rowwise() += linear;
    }
    return regular;
  }
  const SourceNodes sources{owned_rows(nodes_.x), owned_rows(nodes_.weight), owned_rows(nodes_.normal)};
  return regular_layer_sum(sources, owned_rows(u), LayerKernel{Layer::double_, 0.0}, nodes_.x,
                           coincident_sources(nodes_.size(), first, n));
}

std::vector<int> CellLayers::halo_with(const std::vector<SlabPlanes>& other_slabs) const {
  if (owns_all()) return {};
  if (!spheres_.empty()) return cell_halo(spheres_, owned_, domain_.box, halo_extent_, other_slabs);
  const int np = nodes_per_cell();  // every cell held
  std::vector<CellSphere> spheres;
  for (int c = 0; c < num_cells_; ++c) spheres.push_back(bounding_sphere(nodes_.x.middleRows(c * np, np)));
  return cell_halo(spheres, owned_, domain_.box, halo_extent_, other_slabs);
}

std::vector<int> cell_layers_halo(const std::vector<CellSphere>& spheres, const CellGrids& grids,
                                  const LayerDomain& domain, const QuadratureOptions& options,
                                  bool with_double_layer, SpmeGridCache* grid_cache,
                                  const std::vector<SlabPlanes>& other_slabs) {
  const int nc = static_cast<int>(spheres.size());
  const OwnedRange owned = owned_cells(nc, domain);
  if (owned.size() == nc) return {};
  // The layers' extent (CellLayers's constructor), the owned cells' near distances from their
  // areas, the grids from the cache.
  double near_reach = 0.0;
  for (int c = owned.begin; c < owned.end; ++c)
    near_reach = std::max(near_reach, cell_near_reach(spheres[c].area, grids.order, options));
  std::shared_ptr<const SpmeGrid> single_grid, double_grid;
  if (domain.box) {
    const long nodes = static_cast<long>(nc) * grids.n_grid->grid().size();
    single_grid = cell_layer_grid(domain, nodes, false, grid_cache);
    if (with_double_layer) double_grid = cell_layer_grid(domain, nodes, true, grid_cache);
  }
  return cell_halo(spheres, owned, domain.box, layers_halo_extent(near_reach, single_grid.get(), double_grid.get()),
                   other_slabs);
}

PairShares CellLayers::take_folded_shares(Layer layer) const {
  // Calls f(cell, target row, patch nodes) for every target of the layer's corrections with
  // folded nodes. Sources are numbered within the owned block (the plans' sources).
  const Eigen::Index first = owned_nodes().begin;
  auto for_each_target = [&](auto&& f) {
    for (int c = owned_.begin; c < owned_.end; ++c) {
      const LayerCorrection& self = *(layer == Layer::single ? self_single_ : self_double_)[c];
      for (int t = 0; t < self.num_targets(); ++t)
        if (!self.folded(t).empty()) f(c, static_cast<int>(held_row(c)) + t, self.folded(t));
      const NearCorrection& n = near_[c];
      const LayerCorrection* near = (layer == Layer::single ? n.single : n.double_).get();
      if (!near) continue;
      for (int k = 0; k < near->num_targets(); ++k)
        if (!near->folded(k).empty()) f(c, n.rows[k], near->folded(k));
    }
  };
  // A segment per correction and target, pointing to the correction's folded nodes (which the
  // corrections hold as long as the plans live: no copy of them at the peak of the build).
  PairShares shares;
  shares.offsets.assign(static_cast<std::size_t>(nodes_.size()) + 1, 0);
  for_each_target([&](int, int row, std::span<const PatchNode>) { ++shares.offsets[row + 1]; });
  for (std::size_t r = 1; r < shares.offsets.size(); ++r) shares.offsets[r] += shares.offsets[r - 1];
  shares.segments.resize(shares.offsets.back());
  std::vector<std::int64_t> next(shares.offsets.begin(), shares.offsets.end() - 1);
  for_each_target([&](int c, int row, std::span<const PatchNode> nodes) {
    shares.segments[next[row]++] = {nodes.data(), static_cast<std::int32_t>(nodes.size()),
                                    static_cast<std::int32_t>(held_row(c) - first)};
  });
  return shares;
}

CellLayers::~CellLayers() = default;

int CellLayers::near_targets() const {
  long n = 0;
  for (const auto& nc : near_) n += static_cast<long>(nc.rows.size());
  return static_cast<int>(domain_.ranks.sum(n));
}

Eigen::MatrixXd CellLayers::cell_block(const Eigen::MatrixXd& held, int c) const {
  return held.middleRows(held_row(c), nodes_per_cell());
}

Eigen::MatrixXd CellLayers::apply_corrections(Layer layer, const Eigen::MatrixXd& density) {
  ScopedTimer timer(timings_.applied);
  const int nc = num_cells(), np = nodes_per_cell();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(density.rows(), 3);  // rows of other ranks' cells stay zero
  std::vector<Eigen::MatrixXd> near(nc);
  // One cell per thread at a time (the corrections' own loops then run on that thread): one
  // parallel region per product instead of two per cell, and the density's patch data shared
  // by the cell's self and near corrections.
#pragma omp parallel for schedule(dynamic)
  for (int c = owned_.begin; c < owned_.end; ++c) {
    const Eigen::MatrixXd block = cell_block(density, c);
    const HermiteData data = cells_[c]->patch_data(block);
    out.middleRows(held_row(c), np) = (layer == Layer::single ? self_single_[c] : self_double_[c])->apply(block, data);
    const NearCorrection& n = near_[c];
    if (!n.rows.empty()) near[c] = (layer == Layer::single ? n.single : n.double_)->apply(block, data);
  }
  for (int c = owned_.begin; c < owned_.end; ++c)
    for (std::size_t k = 0; k < near_[c].rows.size(); ++k) out.row(near_[c].rows[k]) += near[c].row(k);
  return out;
}

Eigen::MatrixXd CellLayers::single_layer(const Eigen::MatrixXd& f) {
  Eigen::MatrixXd u = single_layer_part(f);
  domain_.ranks.sum(u);
  return u;
}

Eigen::MatrixXd CellLayers::single_layer_part(const Eigen::MatrixXd& f) {
  if (single_part_) return every_rows(held_single_layer_part(f));
  if (f.rows() != static_cast<Eigen::Index>(num_cells_) * nodes_per_cell() || f.cols() != 3)
    throw std::invalid_argument("CellLayers::single_layer: bad density size");
  Eigen::MatrixXd gathered;
  return every_rows(held_single_layer_part(at_held(f, gathered)));
}

Eigen::MatrixXd CellLayers::held_single_layer_part(const Eigen::MatrixXd& f_held) {
  if (single_part_) {
    if (&f_held != single_density_)
      throw std::logic_error("CellLayers::single_layer: built for one single-layer density, given another");
    return *single_part_;
  }
  if (f_held.rows() != nodes_.size() || f_held.cols() != 3)
    throw std::invalid_argument("CellLayers::single_layer: bad density size");
  return regular_single_layer(f_held) + apply_corrections(Layer::single, f_held);
}

Eigen::MatrixXd CellLayers::double_layer(const Eigen::MatrixXd& u) {
  Eigen::MatrixXd v = double_layer_part(u);
  domain_.ranks.sum(v);
  return v;
}

Eigen::MatrixXd CellLayers::double_layer_part(const Eigen::MatrixXd& u, Eigen::RowVector3d* uniform) {
  if (u.rows() != static_cast<Eigen::Index>(num_cells_) * nodes_per_cell() || u.cols() != 3)
    throw std::invalid_argument("CellLayers::double_layer: bad density size");
  Eigen::MatrixXd gathered;
  return every_rows(held_double_layer_part(at_held(u, gathered), uniform));
}

Eigen::MatrixXd CellLayers::held_double_layer_part(const Eigen::MatrixXd& u_held, Eigen::RowVector3d* uniform) {
  if (u_held.rows() != nodes_.size() || u_held.cols() != 3)
    throw std::invalid_argument("CellLayers::double_layer: bad density size");
  if (!has_double_layer()) throw std::logic_error("CellLayers::double_layer: built without the double layer");
  if (uniform) uniform->setZero();
  return regular_double_layer(u_held, uniform) + apply_corrections(Layer::double_, u_held);
}

std::vector<int> CellLayers::density_rows() const {
  const int np = nodes_per_cell();
  std::vector<int> rows;
  if (owns_all()) {
    rows.resize(static_cast<std::size_t>(nodes_.size()));
    std::iota(rows.begin(), rows.end(), 0);
    return rows;
  }
  for (int i = owned_.begin * np; i < owned_.end * np; ++i) rows.push_back(i);
  if (double_plan_) {
    // The plan's rows are held rows.
    for (const Eigen::Index i : double_plan_->density_rows())
      rows.push_back(held_[static_cast<std::size_t>(i / np)] * np + static_cast<int>(i % np));
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  return rows;
}

void CellLayers::report_memory(MemoryReport& report) const {
  report.add("the held cells' nodes",
             matrix_bytes(nodes_.x) + matrix_bytes(nodes_.normal) + matrix_bytes(nodes_.weight));
  std::size_t geometry = 0;
  for (const auto& c : cells_)
    if (c) geometry += c->memory_bytes();
  report.add("cell geometry", geometry);
  if (single_part_) report.add("single layer of the step's traction", matrix_bytes(*single_part_));
  for (int c = owned_.begin; c < owned_.end; ++c) {
    if (self_single_[c]) self_single_[c]->report_memory(report, "self corrections");
    if (self_double_[c]) self_double_[c]->report_memory(report, "self corrections", !self_single_[c]);
    const NearCorrection& n = near_[c];
    report.add("near corrections: targets", heap_bytes(n.rows));
    if (n.single) n.single->report_memory(report, "near corrections");
    if (n.double_) n.double_->report_memory(report, "near corrections", !n.single);
  }
  if (single_plan_) single_plan_->report_memory(report, "cell Ewald single");
  if (double_plan_) double_plan_->report_memory(report, "cell Ewald double");
}

}  // namespace rbcflow
