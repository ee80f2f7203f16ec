#include "singular_quadrature.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <stdexcept>

#include "libsolver/quadrature/batch_math.h"
#include "libsolver/quadrature/polar_patch.h"

namespace rbcflow {
namespace {

std::array<double, 6> pack(const Eigen::Matrix3d& k) {
  return {k(0, 0), k(0, 1), k(0, 2), k(1, 1), k(1, 2), k(2, 2)};
}

// The same in single precision (compact_tables), rounded from the double kernel.
std::array<float, 6> pack_rounded(const Eigen::Matrix3d& k) {
  const std::array<double, 6> d = pack(k);
  return {static_cast<float>(d[0]), static_cast<float>(d[1]), static_cast<float>(d[2]),
          static_cast<float>(d[3]), static_cast<float>(d[4]), static_cast<float>(d[5])};
}

Eigen::Vector3d unit_direction(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

template <class Scalar>
Eigen::Vector3d times(const std::array<Scalar, 6>& packed, const Eigen::Vector3d& v) {
  const double k[6] = {packed[0], packed[1], packed[2], packed[3], packed[4], packed[5]};
  return {k[0] * v[0] + k[1] * v[1] + k[2] * v[2], k[1] * v[0] + k[3] * v[1] + k[4] * v[2],
          k[2] * v[0] + k[4] * v[1] + k[5] * v[2]};
}

}  // namespace

// The finest mode on the grid (degree ~ N) has sqrt(N) wavelengths across the patch radius
// rho_1 = 2 pi / sqrt(N): three Gauss points per wavelength. Two (the former default, 8 at
// N = 12) missed the l = 10 relaxation rate by 1.1%; nine or more points give <= 0.3%.
int default_radial_points(int order) {
  return std::max(8, static_cast<int>(std::ceil(3.0 * std::sqrt(static_cast<double>(order)))));
}

CellQuadratureGeometry::CellQuadratureGeometry(const SHCoeffs& x, std::shared_ptr<const CellGrids> grids,
                                               const QuadratureOptions& options)
    : grids_(std::move(grids)), options_(options) {
  if (!grids_) throw std::invalid_argument("CellQuadratureGeometry: no grids");
  const int N = grids_->order;
  if (x.order() > N || x.components() != 3) {
    throw std::invalid_argument("CellQuadratureGeometry: need 3-component coefficients of order <= " + std::to_string(N));
  }
  if (options_.spline_refinement < 1 || options_.patch_radius_factor <= 0) {
    throw std::invalid_argument("CellQuadratureGeometry: bad quadrature options");
  }
  x_ = x.resampled(N);
  const SurfaceGeometry g = surface_geometry(x_, *grids_->n_grid);
  nodes_.x = g.x;
  nodes_.normal = g.normal;
  nodes_.weight = g.area_weight;

  // J n = (a1 x a2) / sin(theta): smooth on the sphere; its expansion to order 2N (or the
  // Hermite grid's limit) from a 2N Gauss grid.
  const int r = options_.spline_refinement;
  const int jn_order = std::min(2 * N, r * N);
  const SHTransform fine(jn_order, SphGrid::gauss(jn_order), 1);
  const Eigen::MatrixXd a1 = fine.synthesize(x_, 1, 0), a2 = fine.synthesize(x_, 0, 1);
  Eigen::MatrixXd jn(fine.grid().size(), 3);
  for (int p = 0; p < fine.grid().size(); ++p) {
    const double s = std::sin(fine.grid().theta()[p / fine.grid().n_phi()]);
    jn.row(p) = Eigen::Vector3d(a1.row(p)).cross(Eigen::Vector3d(a2.row(p))) / s;
  }
  jn_ = fine.analyze(jn);
  interp_ = std::make_shared<const HermiteInterpolator>(r * N, 1);
  x_data_ = interp_->node_data(x_);
  jn_data_ = interp_->node_data(jn_);
  rho1_ = std::min(std::numbers::pi, options_.patch_radius_factor * std::numbers::pi / std::sqrt(double(N)));
  h_ = cell_mesh_size(surface_area(g), N);
  near_ = cell_near_distance(h_, options_);
}

SourceNodes cell_nodes(const SHCoeffs& x, const CellGrids& grids) {
  const SurfaceGeometry g = surface_geometry(x.resampled(grids.order), *grids.n_grid);
  SourceNodes nodes;
  nodes.x = g.x;
  nodes.normal = g.normal;
  nodes.weight = g.area_weight;
  return nodes;
}

std::vector<QuadratureTarget> CellQuadratureGeometry::node_targets() const {
  const SphGrid& grid = grids_->n_grid->grid();
  std::vector<QuadratureTarget> t(grid.size());
  for (int p = 0; p < grid.size(); ++p) {
    t[p].x = nodes_.x.row(p);
    t[p].theta = grid.theta()[p / grid.n_phi()];
    t[p].phi = grid.phi(p % grid.n_phi());
    t[p].self_node = p;
  }
  return t;
}

HermiteData CellQuadratureGeometry::patch_data(const Eigen::MatrixXd& density) const {
  if (density.rows() != grids_->n_grid->grid().size() || density.cols() != 3)
    throw std::invalid_argument("CellQuadratureGeometry::patch_data: density must be (cell nodes x 3)");
  return interp_->node_data(grids_->n_grid->analyze(density));
}

void CellQuadratureGeometry::geometry_at(const HermiteStencil& s, Eigen::Vector3d& x, Eigen::Vector3d& jn,
                                         int phi_shift) const {
  interp_->interpolate<3>(x_data_, s, x, phi_shift);
  interp_->interpolate<3>(jn_data_, s, jn, phi_shift);
}

LayerCorrection::LayerCorrection(std::shared_ptr<const CellQuadratureGeometry> cell, LayerKernel kernel,
                                 std::vector<QuadratureTarget> targets, NodeShares shares)
    : LayerCorrection(std::move(cell), kernel, std::move(targets), shares, Unbuilt{}) {
  LayerCorrection* self = this;
  build({&self, 1});
}

LayerCorrection::LayerCorrection(std::shared_ptr<const CellQuadratureGeometry> cell, LayerKernel kernel,
                                 std::vector<QuadratureTarget> targets, NodeShares shares, Unbuilt)
    : cell_(std::move(cell)), kernel_(kernel), targets_(std::move(targets)), shares_(shares) {}

std::pair<std::unique_ptr<LayerCorrection>, std::unique_ptr<LayerCorrection>> LayerCorrection::single_and_double(
    const std::shared_ptr<const CellQuadratureGeometry>& cell, double xi_single, double xi_double,
    const std::vector<QuadratureTarget>& targets, std::array<NodeShares, 2> shares) {
  std::unique_ptr<LayerCorrection> single(
      new LayerCorrection(cell, LayerKernel{Layer::single, xi_single}, targets, shares[0], Unbuilt{}));
  std::unique_ptr<LayerCorrection> double_(
      new LayerCorrection(cell, LayerKernel{Layer::double_, xi_double}, targets, shares[1], Unbuilt{}));
  LayerCorrection* both[2] = {single.get(), double_.get()};
  build(both);
  return {std::move(single), std::move(double_)};
}

void LayerCorrection::build(std::span<LayerCorrection* const> corrections) {
  const LayerCorrection& first = *corrections[0];
  const CellQuadratureGeometry& cell = *first.cell_;
  const QuadratureOptions& o = cell.options();
  const HermiteInterpolator& interp = cell.interpolator();
  const int N = cell.grids().order;
  const int n_rho = o.radial_points > 0 ? o.radial_points : default_radial_points(N);
  const int n_varphi = o.angular_points > 0 ? o.angular_points : 2 * n_rho;
  const double rho1 = cell.patch_radius(), cos_rho1 = std::cos(rho1);
  const SphGrid& grid = cell.grids().n_grid->grid();
  const SourceNodes& nodes = cell.nodes();
  const std::vector<QuadratureTarget>& targets = first.targets_;
  const int n_targets = static_cast<int>(targets.size());

  // Tables of patch stencils: one per ring of node targets (the patch of the ring's node at
  // phi = 0, shifted by whole Hermite cells for the others), one per other target.
  auto stencils = std::make_shared<PatchStencils>();
  stencils->table.resize(n_targets);
  stencils->phi_shift.assign(n_targets, 0);
  const bool rings = interp.n_phi() % grid.n_phi() == 0;
  const int cells_per_node = interp.n_phi() / grid.n_phi();
  std::vector<int> ring_table(grid.n_theta(), -1);
  struct TableCentre {
    double theta, phi;
    int target;  // the target whose geometry sets the parametric distance, or -1 (on the surface)
  };
  std::vector<TableCentre> centres;
  const GaussLegendreRule radial = gauss_legendre(n_rho);
  for (int t = 0; t < n_targets; ++t) {
    const QuadratureTarget& target = targets[t];
    const int i = target.self_node / grid.n_phi(), j = target.self_node % grid.n_phi();
    const bool at_node = rings && target.self_node >= 0 && target.distance == 0.0 &&
                         target.theta == grid.theta()[i] && target.phi == grid.phi(j);
    if (!at_node) {
      stencils->table[t] = static_cast<int>(centres.size());
      centres.push_back({target.theta, target.phi, t});
      continue;
    }
    if (ring_table[i] < 0) {
      ring_table[i] = static_cast<int>(centres.size());
      centres.push_back({grid.theta()[i], grid.phi(0), -1});
    }
    stencils->table[t] = ring_table[i];
    stencils->phi_shift[t] = j * cells_per_node;
  }
  const int n_tables = static_cast<int>(centres.size());
  const std::size_t per_table = static_cast<std::size_t>(n_rho) * n_varphi;
  stencils->points_per_table = per_table;
  stencils->tables = static_cast<std::size_t>(n_tables);
  stencils->points = std::make_unique_for_overwrite<HermiteStencil[]>(n_tables * per_table);
  // The products' stencils (compact_tables; the double ones serve the kernels' build only):
  // tables that rings of node targets share keep their weights, read by every target of the
  // ring; tables of one target (off-surface targets) keep only the points' places, 12 bytes.
  const bool shared_tables = std::all_of(centres.begin(), centres.end(), [](const TableCentre& c) { return c.target < 0; });
  if (o.compact_tables && !shared_tables)
    stencils->compact = std::make_unique_for_overwrite<CompactHermiteStencil[]>(n_tables * per_table);
  const auto weights = std::make_unique_for_overwrite<double[]>(n_tables * per_table);
  // Directions of the grid nodes on the parameter sphere: a node is in a patch when
  // u_node . u_centre > cos(rho_1), which needs no trigonometry per (centre, node) pair.
  Eigen::MatrixXd u(grid.size(), 3);
  for (int p = 0; p < grid.size(); ++p) u.row(p) = unit_direction(grid.theta()[p / grid.n_phi()], grid.phi(p % grid.n_phi()));
  // The regular rule's nodes inside each table's patch with their eta (shifted with the
  // stencils for the node targets of a ring): table b's are [b * grid.size(), + count[b]).
  if (grid.size() > PatchNode::kMaxNodes)
    throw std::invalid_argument("LayerCorrection: a cell of " + std::to_string(grid.size()) +
                                " nodes (patch nodes are numbered below " + std::to_string(PatchNode::kMaxNodes) + ")");
  const auto patch_nodes = std::make_unique_for_overwrite<PatchNode[]>(static_cast<std::size_t>(n_tables) * grid.size());
  std::vector<int> patch_node_count(n_tables, 0);
#pragma omp parallel
  {
    // The candidates of one table (nodes with cos rho > cos rho_1): node, sin and cos of rho,
    // then rho and eta, computed a table at a time (batch_math.h).
    std::vector<int> candidate(grid.size());
    std::vector<double> sin_rho(grid.size()), cos_rho(grid.size()), rho(grid.size()), eta(grid.size());
#pragma omp for schedule(dynamic, 4)
    for (int b = 0; b < n_tables; ++b) {
      const TableCentre& centre = centres[b];
      const Eigen::Vector3d uc = unit_direction(centre.theta, centre.phi);
      PatchNode* listed = patch_nodes.get() + static_cast<std::size_t>(b) * grid.size();
      std::size_t n = 0;
      for (int p = 0; p < grid.size(); ++p) {
        const Eigen::Vector3d up = u.row(p).transpose();
        const double c = uc.dot(up);
        if (c <= cos_rho1) continue;
        candidate[n] = p;
        cos_rho[n] = c;
        sin_rho[n++] = uc.cross(up).norm();
      }
      batch_atan2(sin_rho.data(), cos_rho.data(), rho.data(), n);
      batch_patch_mask(rho.data(), rho1, eta.data(), n);
      for (std::size_t k = 0; k < n; ++k)
        if (rho[k] < rho1) listed[patch_node_count[b]++] = PatchNode(candidate[k], static_cast<float>(eta[k]));
      double delta = 0.0;  // parametric distance of an off-surface target: distance over the local length scale
      if (centre.target >= 0 && targets[centre.target].distance > 0) {
        Eigen::Vector3d xc, jc;
        cell.geometry_at(interp.stencil(centre.theta, centre.phi), xc, jc);
        delta = targets[centre.target].distance / std::sqrt(jc.norm());
      }
      const std::vector<PatchPoint> patch = polar_patch(centre.theta, centre.phi, rho1, radial, n_varphi, delta);
      for (std::size_t q = 0; q < per_table; ++q) {
        stencils->points[b * per_table + q] = interp.stencil(patch[q].theta, patch[q].phi);
        if (stencils->compact) stencils->compact[b * per_table + q] = interp.compact_stencil(patch[q].theta, patch[q].phi);
        weights[b * per_table + q] = patch[q].weight;
      }
    }
  }
  // The patch nodes of target t (its table's, shifted with its stencils), but its own node.
  const auto for_each_patch_node = [&](int t, auto&& f) {
    const int node_shift = rings ? stencils->phi_shift[t] / cells_per_node : 0;
    const int b = stencils->table[t];
    for (const PatchNode& centred :
         std::span<const PatchNode>(patch_nodes.get() + static_cast<std::size_t>(b) * grid.size(), patch_node_count[b])) {
      const int i = centred.node() / grid.n_phi();
      int j = centred.node() % grid.n_phi() + node_shift;
      if (j >= grid.n_phi()) j -= grid.n_phi();
      const int p = i * grid.n_phi() + j;
      if (p != targets[t].self_node) f(p, centred.eta());
    }
  };
  // Storage in one array per kind and correction (targets in order), sized first: the node
  // entries a correction keeps or folds depend on the distances.
  for (LayerCorrection* c : corrections) {
    c->stencils_ = stencils;
    for (std::vector<std::int64_t>* offsets : {&c->patch_offsets_, &c->node_offsets_, &c->folded_offsets_})
      offsets->assign(n_targets + 1, 0);
  }
#pragma omp parallel for schedule(dynamic, 64)
  for (int t = 0; t < n_targets; ++t) {
    for (LayerCorrection* c : corrections)
      c->patch_offsets_[t + 1] = static_cast<std::int64_t>(per_table);
    for_each_patch_node(t, [&](int p, double) {
      const double distance = (Eigen::Vector3d(nodes.x.row(p)) - targets[t].x).norm();
      for (LayerCorrection* c : corrections)
        if (distance < c->shares_.reach) ++(distance < c->shares_.fold ? c->folded_offsets_ : c->node_offsets_)[t + 1];
    });
  }
  for (LayerCorrection* c : corrections) {
    for (std::vector<std::int64_t>* offsets : {&c->patch_offsets_, &c->node_offsets_, &c->folded_offsets_})
      for (int t = 0; t < n_targets; ++t) (*offsets)[t + 1] += (*offsets)[t];
    if (o.compact_tables) {
      c->patch_kf_.resize(c->patch_offsets_.back());
    } else {
      c->patch_k_.resize(c->patch_offsets_.back());
    }
    if (o.compact_tables && c->kernel_.layer() == Layer::double_) {
      c->nodes_f_.resize(c->node_offsets_.back());
    } else {
      c->nodes_.resize(c->node_offsets_.back());
    }
    c->folded_.resize(c->folded_offsets_.back());
  }

#pragma omp parallel for schedule(dynamic, 4)
  for (int t = 0; t < n_targets; ++t) {
    const QuadratureTarget& target = targets[t];
    const std::span<const HermiteStencil> table = stencils->of_target(stencils->points, t);
    const double* weight = weights.get() + static_cast<std::size_t>(stencils->table[t]) * per_table;
    const int shift = stencils->phi_shift[t];
    // The patch centre as the interpolant sees it: r = x_q - x0 is measured from it so that
    // the kernel's singularity sits exactly at rho = 0 (an offset of the interpolation error
    // would spoil r . n ~ rho^2 in the double layer). Off-surface targets keep their offset.
    Eigen::Vector3d xc, jc;
    cell.geometry_at(interp.stencil(target.theta, target.phi), xc, jc);
    const Eigen::Vector3d x0 = target.self_node >= 0 ? xc : Eigen::Vector3d(target.x);
    for (std::size_t q = 0; q < table.size(); ++q) {
      Eigen::Vector3d xq, jn;
      cell.geometry_at(table[q], xq, jn, shift);
      const Eigen::Vector3d r = xq - x0;
      for (LayerCorrection* c : corrections) {
        const bool single = c->kernel_.layer() == Layer::single;
        const Eigen::Matrix3d k = single ? Eigen::Matrix3d(c->kernel_.matrix(r, jn) * (jn.norm() * weight[q]))
                                         : Eigen::Matrix3d(c->kernel_.matrix(r, jn * weight[q]));
        const std::size_t at = static_cast<std::size_t>(c->patch_offsets_[t]) + q;
        if (o.compact_tables) {
          c->patch_kf_[at] = pack_rounded(k);
        } else {
          c->patch_k_[at] = pack(k);
        }
      }
    }
    // The regular rule's share of the patch, eta K w at the nodes inside it, is removed here,
    // or by the caller for the nodes within its fold radius; none beyond the reach.
    std::array<std::int64_t, 2> kept{}, folded{};  // cursors (one or two corrections)
    for (std::size_t i = 0; i < corrections.size(); ++i) {
      kept[i] = corrections[i]->node_offsets_[t];
      folded[i] = corrections[i]->folded_offsets_[t];
    }
    std::int64_t unvisited = 0;  // patch nodes of the target not yet visited, this one included
    for_each_patch_node(t, [&](int, float) { ++unvisited; });
    for_each_patch_node(t, [&](int p, float eta) {
      const Eigen::Vector3d r = Eigen::Vector3d(nodes.x.row(p)) - target.x;
      const double distance = r.norm();
      const Eigen::Vector3d m = nodes.weight[p] * Eigen::Vector3d(nodes.normal.row(p));
      for (std::size_t i = 0; i < corrections.size(); ++i) {
        LayerCorrection* c = corrections[i];
        // As counted above; should the compiler round the distance differently here, a node
        // at the reach or the fold radius may change sides: the target's ranges are filled,
        // never overrun.
        const std::int64_t open = c->node_offsets_[t + 1] - kept[i] + c->folded_offsets_[t + 1] - folded[i];
        bool beyond = distance >= c->shares_.reach;
        if (beyond && open == unvisited) beyond = false;
        if (!beyond && open == 0) beyond = true;
        if (beyond) continue;
        bool fold = distance < c->shares_.fold;
        if (fold && folded[i] == c->folded_offsets_[t + 1]) fold = false;
        if (!fold && kept[i] == c->node_offsets_[t + 1]) fold = true;
        if (fold) {
          c->folded_[folded[i]++] = PatchNode(p, static_cast<float>(eta));
          continue;
        }
        const bool single = c->kernel_.layer() == Layer::single;
        const Eigen::Matrix3d k = single ? Eigen::Matrix3d(c->kernel_.matrix(r, m) * (-eta * nodes.weight[p]))
                                         : Eigen::Matrix3d(c->kernel_.matrix(r, m) * (-eta));
        if (o.compact_tables && !single) {
          c->nodes_f_[kept[i]++] = {p, pack_rounded(k)};
        } else {
          c->nodes_[kept[i]++] = {p, pack(k)};
        }
      }
      --unvisited;
    });
  }
  if (!o.compact_tables) return;
  if (shared_tables) {
    const std::size_t points = static_cast<std::size_t>(n_tables) * per_table;
    stencils->floats = std::make_unique_for_overwrite<FloatHermiteStencil[]>(points);
#pragma omp parallel for schedule(static)
    for (std::size_t q = 0; q < points; ++q) stencils->floats[q] = FloatHermiteStencil::of(stencils->points[q]);
  }
  stencils->points.reset();
}

Eigen::MatrixXd LayerCorrection::apply(const Eigen::MatrixXd& density) const {
  return apply(density, cell_->patch_data(density));
}

Eigen::MatrixXd LayerCorrection::apply(const Eigen::MatrixXd& density, const SHCoeffs& c) const {
  if (c.components() != 3 || c.order() > cell_->interpolator().order()) {
    throw std::invalid_argument("LayerCorrection::apply: the patch density needs an expansion of order <= " +
                                std::to_string(cell_->interpolator().order()));
  }
  return apply(density, cell_->interpolator().node_data(c));
}

Eigen::MatrixXd LayerCorrection::apply(const Eigen::MatrixXd& density, const HermiteData& data) const {
  const HermiteInterpolator& interp = cell_->interpolator();
  if (density.rows() != cell_->grids().n_grid->grid().size() || density.cols() != 3 ||
      data.rows() != static_cast<Eigen::Index>(interp.n_theta()) * interp.n_phi() || data.cols() != 12) {
    throw std::invalid_argument("LayerCorrection::apply: density must be (cell nodes x 3), its Hermite data (" +
                                std::to_string(interp.n_theta() * interp.n_phi()) + " x 12)");
  }
  Eigen::MatrixXd out(num_targets(), 3);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < num_targets(); ++t) {
    const auto with_nodes = [&](const auto& stencils, const auto* kernels) {
      return nodes_f_.empty() ? correction_at(t, stencils, kernels, nodes_.data(), density, data)
                              : correction_at(t, stencils, kernels, nodes_f_.data(), density, data);
    };
    if (stencils_->floats) {
      out.row(t) = with_nodes(stencils_->floats, patch_kf_.data());
    } else if (stencils_->compact) {
      out.row(t) = with_nodes(stencils_->compact, patch_kf_.data());
    } else {
      out.row(t) = with_nodes(stencils_->points, patch_k_.data());
    }
  }
  return out;
}

template <class Stencil, class Kernel, class NodeKernel>
Eigen::Vector3d LayerCorrection::correction_at(int t, const std::unique_ptr<Stencil[]>& stencils, const Kernel* kernels,
                                               const NodeEntry<NodeKernel>* node_entries, const Eigen::MatrixXd& density,
                                               const HermiteData& data) const {
  const HermiteInterpolator& interp = cell_->interpolator();
  const std::span<const Stencil> table = stencils_->of_target(stencils, t);
  const Kernel* k = kernels + patch_offsets_[t];
  const int shift = stencils_->phi_shift[t];
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t q = 0; q < table.size(); ++q) {
    Eigen::Vector3d psi;
    interp.interpolate<3>(data, table[q], psi, shift);
    sum += times(k[q], psi);
  }
  for (std::int64_t i = node_offsets_[t]; i < node_offsets_[t + 1]; ++i)
    sum += times(node_entries[i].k, Eigen::Vector3d(density.row(node_entries[i].node)));
  return sum;
}

Eigen::MatrixXd free_space_layer_on_nodes(const std::shared_ptr<const CellQuadratureGeometry>& cell,
                                          Layer layer, const Eigen::MatrixXd& density,
                                          const SHCoeffs& patch_density) {
  const LayerKernel kernel{layer, 0.0};
  const std::vector<QuadratureTarget> targets = cell->node_targets();
  std::vector<int> self(targets.size());
  for (std::size_t t = 0; t < targets.size(); ++t) self[t] = targets[t].self_node;
  const Eigen::MatrixXd x0 = cell->nodes().x;
  const LayerCorrection correction(cell, kernel, targets);
  return regular_layer_sum(cell->nodes(), density, kernel, x0, self) +
         (patch_density.order() > 0 ? correction.apply(density, patch_density) : correction.apply(density));
}

std::size_t CellQuadratureGeometry::memory_bytes() const {
  return matrix_bytes(x_.values()) + matrix_bytes(jn_.values()) + matrix_bytes(nodes_.x) + matrix_bytes(nodes_.normal) +
         matrix_bytes(nodes_.weight) + matrix_bytes(x_data_) + matrix_bytes(jn_data_);
}

std::size_t LayerCorrection::PatchStencils::memory_bytes() const {
  const std::size_t n = tables * points_per_table;
  return (points ? n * sizeof(HermiteStencil) : 0) + (floats ? n * sizeof(FloatHermiteStencil) : 0) +
         (compact ? n * sizeof(CompactHermiteStencil) : 0) +
         heap_bytes(table) + heap_bytes(phi_shift);
}

void LayerCorrection::report_memory(MemoryReport& report, const std::string& prefix, bool with_stencils) const {
  if (with_stencils && stencils_) report.add(prefix + ": patch stencils", stencils_->memory_bytes());
  report.add(prefix + ": patch kernels", heap_bytes(patch_k_) + heap_bytes(patch_kf_) + heap_bytes(patch_offsets_));
  report.add(prefix + ": node entries", heap_bytes(nodes_) + heap_bytes(nodes_f_) + heap_bytes(node_offsets_));
  report.add(prefix + ": folded nodes", heap_bytes(folded_) + heap_bytes(folded_offsets_));
  report.add(prefix + ": targets", heap_bytes(targets_));
}

}  // namespace rbcflow
