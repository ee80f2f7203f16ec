#include "cell_layers_at_points.h"

#include <stdexcept>
#include <tuple>

#include "libsolver/quadrature/regular_quadrature.h"
#include "libsolver/spme/double_layer_linear.h"
#include "near_targets.h"

namespace rbcflow {

CellLayersAtPoints::CellLayersAtPoints(const CellLayers& layers, const Eigen::MatrixXd& points)
    : layers_(layers), points_(points) {
  const LayerDomain& domain = layers.domain();
  const int nc = layers.num_cells();
  const long ns = layers.nodes().size();
  const bool with_double = layers.has_double_layer();
  double xi_single = 0.0, xi_double = 0.0;
  if (domain.box) {
    const PeriodicBox& box = *domain.box;
    auto plan = [&](EwaldKernel kernel, double& xi) {
      auto grid = ewald_grid(layers.grid_cache(), kernel, domain.ewald_tolerance, box, ns, points_.rows());
      xi = grid->parameters().xi;
      return std::make_unique<EwaldPlan>(std::move(grid), layers.nodes().x, points_);
    };
    single_plan_ = plan(EwaldKernel::stokeslet, xi_single);
    if (with_double) double_plan_ = plan(EwaldKernel::stresslet, xi_double);
  }
  near_.resize(nc);
#pragma omp parallel for schedule(dynamic)
  for (int c = 0; c < nc; ++c) {
    NearTargets near = find_near_targets(layers.cell(c), points_, domain.box);
    if (near.targets.empty()) continue;
    near_[c].rows = std::move(near.rows);
    if (with_double) {
      std::tie(near_[c].single, near_[c].double_) =
          LayerCorrection::single_and_double(layers.cell_geometry(c), xi_single, xi_double, near.targets);
    } else {
      near_[c].single = std::make_unique<LayerCorrection>(layers.cell_geometry(c), LayerKernel{Layer::single, xi_single},
                                                          near.targets);
    }
  }
}

CellLayersAtPoints::~CellLayersAtPoints() = default;

int CellLayersAtPoints::near_points() const {
  int n = 0;
  for (const Near& c : near_) n += static_cast<int>(c.rows.size());
  return n;
}

Eigen::MatrixXd CellLayersAtPoints::corrections(Layer layer, const Eigen::MatrixXd& density) const {
  const int nc = layers_.num_cells(), np = layers_.nodes_per_cell();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(points_.rows(), 3);
  std::vector<Eigen::MatrixXd> near(nc);
#pragma omp parallel for schedule(dynamic)  // one cell per thread at a time, as in CellLayers
  for (int c = 0; c < nc; ++c) {
    const Near& n = near_[c];
    if (!n.rows.empty()) near[c] = (layer == Layer::single ? n.single : n.double_)->apply(density.middleRows(c * np, np));
  }
  for (int c = 0; c < nc; ++c)
    for (std::size_t k = 0; k < near_[c].rows.size(); ++k) out.row(near_[c].rows[k]) += near[c].row(k);
  return out;
}

Eigen::MatrixXd CellLayersAtPoints::single_layer(const Eigen::MatrixXd& f) const {
  const SourceNodes& nodes = layers_.nodes();
  if (f.rows() != nodes.size() || f.cols() != 3) throw std::invalid_argument("CellLayersAtPoints::single_layer: bad density size");
  Eigen::MatrixXd regular;
  if (single_plan_) {
    regular = single_plan_->single_layer(f.array().colwise() * nodes.weight.array());
  } else {
    regular = regular_layer_sum(nodes, f, LayerKernel{Layer::single, 0.0}, points_);
  }
  return regular + corrections(Layer::single, f);
}

Eigen::MatrixXd CellLayersAtPoints::double_layer(const Eigen::MatrixXd& u) const {
  const SourceNodes& nodes = layers_.nodes();
  if (u.rows() != nodes.size() || u.cols() != 3) throw std::invalid_argument("CellLayersAtPoints::double_layer: bad density size");
  if (!layers_.has_double_layer()) throw std::logic_error("CellLayersAtPoints::double_layer: built without the double layer");
  Eigen::MatrixXd regular;
  if (double_plan_) {
    const PointField q = u.array().colwise() * nodes.weight.array();
    regular = double_plan_->double_layer(q, nodes.normal);
    regular.rowwise() += double_layer_linear_part(*layers_.domain().box, nodes.x, q, nodes.normal, layers_.nodes_per_cell());
  } else {
    regular = regular_layer_sum(nodes, u, LayerKernel{Layer::double_, 0.0}, points_);
  }
  return regular + corrections(Layer::double_, u);
}

void CellLayersAtPoints::report_memory(MemoryReport& report, const std::string& prefix) const {
  report.add(prefix + " near corrections: targets", matrix_bytes(points_));
  for (const Near& n : near_) {
    report.add(prefix + " near corrections: targets", heap_bytes(n.rows));
    if (n.single) n.single->report_memory(report, prefix + " near corrections");
    if (n.double_) n.double_->report_memory(report, prefix + " near corrections", false);
  }
  if (single_plan_) single_plan_->report_memory(report, prefix + " Ewald single");
  if (double_plan_) double_plan_->report_memory(report, prefix + " Ewald double");
}

}  // namespace rbcflow
