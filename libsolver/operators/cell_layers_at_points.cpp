#include "cell_layers_at_points.h"

#include <array>
#include <stdexcept>
#include <tuple>

#include "libsolver/quadrature/regular_quadrature.h"
#include "libsolver/spme/double_layer_linear.h"
#include "near_targets.h"

namespace rbcflow {

std::shared_ptr<const SpmeGrid> cell_layers_at_points_grid(const LayerDomain& domain, EwaldKernel kernel, long nodes,
                                                           long points, SpmeGridCache* grid_cache) {
  if (!domain.box) throw std::invalid_argument("cell_layers_at_points_grid: free space has no grid");
  return ewald_grid(grid_cache, kernel, domain.ewald_tolerance, *domain.box, nodes, points, {}, domain.ranks);
}

CellLayersAtPoints::CellLayersAtPoints(const CellLayers& layers, const Eigen::MatrixXd& points,
                                       const Eigen::MatrixXd* single_layer_density, const DensityHalo& bring_density)
    : layers_(layers), points_(points) {
  if (single_layer_density) {
    if (single_layer_density->rows() != layers.nodes().size() || single_layer_density->cols() != 3)
      throw std::invalid_argument("CellLayersAtPoints: the single-layer density must be (held cell nodes x 3)");
    single_density_ = single_layer_density;
  }
  const LayerDomain& domain = layers.domain();
  const int nc = layers.num_cells();
  const long ns = static_cast<long>(nc) * layers.nodes_per_cell();  // every cell's nodes
  const OwnedRange& owned = layers.owned();
  const int np = layers.nodes_per_cell();
  const bool with_double = layers.has_double_layer();
  double xi_single = 0.0, xi_double = 0.0;
  // The corrections remove the shares of the patch nodes within the real-space cutoff: the
  // sums hold no pair beyond it (NodeShares::reach).
  std::array<NodeShares, 2> node_shares{};
  if (domain.box) {
    // The grid chosen for all the cells' nodes; the owned cells' nodes are this rank's
    // real-space sources (ewald_plan.h), the held ones those that spread into its slab. A rank
    // without cells takes part in the transforms of a grid split over the ranks.
    auto plan = [&](EwaldKernel kernel, double& xi, NodeShares& shares) -> std::unique_ptr<EwaldPlan> {
      auto grid = cell_layers_at_points_grid(domain, kernel, ns, points_.rows(), layers.grid_cache());
      xi = grid->parameters().xi;
      shares.reach = grid->parameters().cutoff;
      if (owned.empty() && !grid->distributed()) return nullptr;
      if (const std::optional<SlabPlanes> slab = rank_slab(*grid)) slabs_.push_back(*slab);
      // No kept pair coefficients: a step applies each layer here once (the single layer in
      // the build, the double layer in (12)), but for the first step's start sweeps; kept, they
      // would be filled once and held at the step's peak for nothing.
      auto p = std::make_unique<EwaldPlan>(std::move(grid), layers.nodes().x, points_, layers.owned_nodes());
      p->keep_pairs_up_to(0);
      return p;
    };
    single_plan_ = plan(EwaldKernel::stokeslet, xi_single, node_shares[0]);
    if (with_double) double_plan_ = plan(EwaldKernel::stresslet, xi_double, node_shares[1]);
  }
  if (single_density_ && bring_density) bring_density(layers.halo_with(slabs_));
  near_.resize(nc);
  std::vector<Eigen::MatrixXd> near_single(nc);
#pragma omp parallel for schedule(dynamic)
  for (int c = owned.begin; c < owned.end; ++c) {
    NearTargets near = find_near_targets(layers.cell(c), points_, domain.box);
    if (near.targets.empty()) continue;
    near_[c].rows = std::move(near.rows);
    if (with_double) {
      std::tie(near_[c].single, near_[c].double_) =
          LayerCorrection::single_and_double(layers.cell_geometry(c), xi_single, xi_double, near.targets, node_shares);
    } else {
      near_[c].single = std::make_unique<LayerCorrection>(layers.cell_geometry(c), LayerKernel{Layer::single, xi_single},
                                                          near.targets, node_shares[0]);
    }
    if (single_density_) {
      near_single[c] = near_[c].single->apply(single_density_->middleRows(layers.held_row(c), np));
      near_[c].single.reset();
    }
  }
  if (single_density_) {
    Eigen::MatrixXd corrections = Eigen::MatrixXd::Zero(points_.rows(), 3);
    for (int c = owned.begin; c < owned.end; ++c)
      for (std::size_t k = 0; k < near_[c].rows.size(); ++k) corrections.row(near_[c].rows[k]) += near_single[c].row(k);
    single_part_ = regular_single_layer(*single_density_) + corrections;
    single_plan_.reset();
  }
}

Eigen::MatrixXd CellLayersAtPoints::regular_single_layer(const Eigen::MatrixXd& f) const {
  if (layers_.domain().box) {
    if (!single_plan_) return Eigen::MatrixXd::Zero(points_.rows(), 3);  // no cell owned here
    return single_plan_->single_layer(f.array().colwise() * layers_.nodes().weight.array());
  }
  return regular_layer_sum(owned_sources(), owned_nodes(f), LayerKernel{Layer::single, 0.0}, points_);
}

SourceNodes CellLayersAtPoints::owned_sources() const {
  const SourceNodes& nodes = layers_.nodes();
  return {owned_nodes(nodes.x), owned_nodes(nodes.weight), owned_nodes(nodes.normal)};
}

CellLayersAtPoints::~CellLayersAtPoints() = default;


int CellLayersAtPoints::near_points() const {
  long n = 0;
  for (const Near& c : near_) n += static_cast<long>(c.rows.size());
  return static_cast<int>(layers_.domain().ranks.sum(n));
}

Eigen::MatrixXd CellLayersAtPoints::corrections(Layer layer, const Eigen::MatrixXd& density) const {
  const int nc = layers_.num_cells(), np = layers_.nodes_per_cell();
  const OwnedRange& owned = layers_.owned();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(points_.rows(), 3);
  std::vector<Eigen::MatrixXd> near(nc);
#pragma omp parallel for schedule(dynamic)  // one cell per thread at a time, as in CellLayers
  for (int c = owned.begin; c < owned.end; ++c) {
    const Near& n = near_[c];
    if (!n.rows.empty())
      near[c] = (layer == Layer::single ? n.single : n.double_)->apply(density.middleRows(layers_.held_row(c), np));
  }
  for (int c = owned.begin; c < owned.end; ++c)
    for (std::size_t k = 0; k < near_[c].rows.size(); ++k) out.row(near_[c].rows[k]) += near[c].row(k);
  return out;
}

Eigen::MatrixXd CellLayersAtPoints::single_layer(const Eigen::MatrixXd& f) const {
  Eigen::MatrixXd u = single_layer_part(f);
  layers_.domain().ranks.sum(u);
  return u;
}

Eigen::MatrixXd CellLayersAtPoints::double_layer(const Eigen::MatrixXd& u) const {
  Eigen::MatrixXd v = double_layer_part(u);
  layers_.domain().ranks.sum(v);
  return v;
}

Eigen::MatrixXd CellLayersAtPoints::single_layer_part(const Eigen::MatrixXd& f) const {
  if (f.rows() != layers_.nodes().size() || f.cols() != 3) throw std::invalid_argument("CellLayersAtPoints::single_layer: bad density size");
  if (single_part_) {
    if (&f != single_density_)
      throw std::logic_error("CellLayersAtPoints::single_layer: built for one single-layer density, given another");
    return *single_part_;
  }
  return regular_single_layer(f) + corrections(Layer::single, f);
}

Eigen::MatrixXd CellLayersAtPoints::double_layer_part(const Eigen::MatrixXd& u) const {
  const SourceNodes& nodes = layers_.nodes();
  if (u.rows() != nodes.size() || u.cols() != 3) throw std::invalid_argument("CellLayersAtPoints::double_layer: bad density size");
  if (!layers_.has_double_layer()) throw std::logic_error("CellLayersAtPoints::double_layer: built without the double layer");
  Eigen::MatrixXd v;
  if (layers_.domain().box) {
    v = Eigen::MatrixXd::Zero(points_.rows(), 3);
    if (double_plan_) {
      const PointField q = u.array().colwise() * nodes.weight.array();
      v = double_plan_->double_layer(q, nodes.normal);
      const PointField owned_q = owned_nodes(q), owned_normals = owned_nodes(nodes.normal);
      v.rowwise() += double_layer_linear_part(*layers_.domain().box, owned_nodes(nodes.x), owned_q, owned_normals,
                                              layers_.nodes_per_cell());
    }
  } else {
    v = regular_layer_sum(owned_sources(), owned_nodes(u), LayerKernel{Layer::double_, 0.0}, points_);
  }
  v += corrections(Layer::double_, u);
  return v;
}

void CellLayersAtPoints::report_memory(MemoryReport& report, const std::string& prefix) const {
  report.add(prefix + " near corrections: targets", matrix_bytes(points_));
  if (single_part_) report.add(prefix + " single layer of the step's traction", matrix_bytes(*single_part_));
  for (const Near& n : near_) {
    report.add(prefix + " near corrections: targets", heap_bytes(n.rows));
    if (n.single) n.single->report_memory(report, prefix + " near corrections");
    if (n.double_) n.double_->report_memory(report, prefix + " near corrections", !n.single);
  }
  if (single_plan_) single_plan_->report_memory(report, prefix + " Ewald single");
  if (double_plan_) double_plan_->report_memory(report, prefix + " Ewald double");
}

}  // namespace rbcflow
