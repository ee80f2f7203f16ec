#include "wall_operator.h"

#include <stdexcept>
#include <string>

#include "libsolver/common/memory_report.h"
#include "libsolver/kernels/ewald_kernels.h"
#include "libsolver/kernels/stokes_kernels.h"
#include "wall_real_space.h"

namespace rbcflow {

namespace {

PointField wrapped(const PointField& x, const PeriodicBox& box) {
  PointField out(x.rows(), 3);
  for (Eigen::Index i = 0; i < x.rows(); ++i) out.row(i) = box.wrap(x.row(i).transpose()).transpose();
  return out;
}

// The near field's rows for an assembled operator whose rows are given, on more than one rank:
// the rank's segment (the only rows its assembled matrix and preconditioner blocks read).
std::function<bool(int)> at_rows_only(WallOperator::RealSpace real_space, const std::optional<OwnedSegments>& rows,
                                      const Communicator& ranks, long targets) {
  if (rows && rows->total() != targets)
    throw std::invalid_argument("WallOperator: the rows' segments are not of the targets");
  if (real_space != WallOperator::RealSpace::assembled || !rows || ranks.size() == 1) return {};
  return [segments = *rows](int t) { return segments.position(t) >= 0; };
}

}  // namespace

WallOperator::WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets)
    : WallOperator(std::move(elements), targets, std::function<bool(int)>{}) {}

WallOperator::WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets,
                           const std::function<bool(int)>& rows)
    : elements_(std::move(elements)),
      targets_(targets),
      near_(near_field(*elements_, targets_, 3.0, 1.0, rows)),
      segments_(static_cast<int>(targets_.rows()), ranks_),
      near_at_rows_only_(static_cast<bool>(rows)) {
  for (const auto& [t, q] : near_.coincident) targets_.row(t) = elements_->points.row(q);
}

WallOperator::WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets,
                           const PeriodicBox& box, double ewald_tolerance, SpmeGridCache* grid_cache,
                           RealSpace real_space, long chosen_for_targets, Communicator ranks,
                           const RealSpaceUse& assembled_use, std::optional<OwnedSegments> rows)
    : WallOperator(std::move(elements), targets, at_rows_only(real_space, rows, ranks, targets.rows())) {
  ranks_ = ranks;
  segments_ = rows ? std::move(*rows) : OwnedSegments(num_targets(), ranks_);
  const long n = elements_->points.rows();
  const RealSpaceUse use = real_space == RealSpace::assembled ? assembled_use : RealSpaceUse{};
  const double tol = real_space == RealSpace::assembled ? kAssembledToleranceFactor * ewald_tolerance : ewald_tolerance;
  const long m = chosen_for_targets > 0 ? chosen_for_targets : targets.rows();
  // The assembled operator's grid is split over the ranks where it can be (spme_grid.h); an
  // operator at one rank's share of the targets keeps the whole grid (its interpolation must
  // see every plane).
  const Communicator grid_ranks = real_space == RealSpace::assembled ? ranks_ : Communicator{};
  ewald_.emplace(ewald_grid(grid_cache, EwaldKernel::stokeslet, tol, box, n, m, use, grid_ranks),
                 wrapped(elements_->points, box), wrapped(targets_, box));
  if (real_space == RealSpace::assembled) {
    const auto precision = ewald_tolerance >= kSingleBlocksTolerance ? SymmetricBlockMatrix::Precision::single_entries
                                                                     : SymmetricBlockMatrix::Precision::double_entries;
    near_and_real_.emplace(wall_real_space_blocks(*elements_, ewald_->neighbors(), ewald_->xi(),
                                                  Eigen::SparseMatrix<double, Eigen::RowMajor>(near_.correction),
                                                  segments_, precision));
    node_spreading_.emplace(ewald_->smooth().sources().spreading_matrix(elements_->density_map()));
    ewald_->release_real_space();                   // held in near_and_real_ now
    near_.correction = Eigen::SparseMatrix<double>();  // so is this
  }
}

WallOperator::WallOperator(std::shared_ptr<const WallElements> elements, const PointField& targets, TargetRows rows,
                           const PeriodicBox& box, double ewald_tolerance, SpmeGridCache* grid_cache, Communicator ranks,
                           long all_targets)
    : elements_(std::move(elements)),
      targets_(targets),
      target_rows_(rows),
      ranks_(ranks),
      segments_(static_cast<int>(targets_.rows()), ranks_) {
  if (rows.begin < 0 || rows.end < rows.begin || rows.end > targets.rows())
    throw std::invalid_argument("WallOperator: target rows [" + std::to_string(rows.begin) + ", " +
                                std::to_string(rows.end) + ") of " + std::to_string(targets.rows()));
  near_ = near_field(*elements_, targets_.middleRows(rows.begin, rows.end - rows.begin));
  for (const auto& [t, q] : near_.coincident) targets_.row(rows.begin + t) = elements_->points.row(q);
  if (all_targets == 0) all_targets = targets_.rows();
  ewald_.emplace(grid_at_rows(grid_cache, ewald_tolerance, box, elements_->points.rows(), all_targets, ranks_),
                 wrapped(elements_->points, box), wrapped(targets_, box), rows);
  // Applied once a step (the wall's velocity at the cells), but in the first step's start
  // sweeps: kept pair coefficients would be filled once and held for nothing.
  ewald_->keep_pairs_up_to(0);
}

std::shared_ptr<const SpmeGrid> WallOperator::grid_at_rows(SpmeGridCache* grid_cache, double ewald_tolerance,
                                                           const PeriodicBox& box, long wall_points, long targets,
                                                           const Communicator& ranks) {
  return ewald_grid(grid_cache, EwaldKernel::stokeslet, ewald_tolerance, box, wall_points, targets, {}, ranks);
}

const SpmeGrid& WallOperator::grid() const {
  if (!ewald_) throw std::logic_error("WallOperator::grid: a free-space operator has no grid");
  return ewald_->smooth().grid();
}

PointField WallOperator::apply(const PointField& f) {
  if (near_and_real_) return to_field(segments_.gather(apply_mine(f)));
  PointField u;
  const PointField density = elements_->weighted_density(f);
  const Eigen::Index first = target_rows_ ? target_rows_->begin : 0;  // of the near field's targets
  if (ewald_) {
    u = ewald_->single_layer(density);
    const double self = ewald_real_stokeslet_self(ewald_->xi());
    for (const auto& [t, q] : near_.coincident) u.row(first + t) += self * density.row(q);
  } else {
    u = PointField::Zero(targets_.rows(), 3);
    const PointField& y = elements_->points;
#pragma omp parallel for schedule(static)
    for (Eigen::Index t = 0; t < targets_.rows(); ++t) {
      const Eigen::Vector3d x = targets_.row(t).transpose();
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (Eigen::Index s = 0; s < y.rows(); ++s) {
        const Eigen::Vector3d r = y.row(s).transpose() - x;
        if (r.squaredNorm() > 0.0) sum += stokeslet_apply(r, density.row(s).transpose());
      }
      u.row(t) = sum.transpose();
    }
  }
  const Eigen::VectorXd correction = near_.correction * to_vector(f);
  u.middleRows(first, correction.size() / 3) += to_field(correction);
  return u;
}

Eigen::VectorXd WallOperator::apply_mine(const PointField& f) {
  if (!near_and_real_) return segments_.mine(to_vector(apply(f)));
  const bool distributed = ewald_->smooth().grid().distributed();
  // The smooth part: this rank's planes' share at every target on a split grid, else all of it
  // (the same on every rank).
  PointField u = ewald_->smooth_single_layer(*node_spreading_, f);
  if (!near_.coincident.empty() && (!distributed || ranks_.root())) {  // once in the ranks' sum
    const PointField density = elements_->weighted_density(f);
    const double self = ewald_real_stokeslet_self(ewald_->xi());
    for (const auto& [t, q] : near_.coincident) u.row(t) += self * density.row(q);
  }
  Eigen::VectorXd v = *near_and_real_ * to_vector(f);  // this rank's rows, zeros elsewhere
  v += to_vector(u);
  // Only a split grid's smooth part needs the other ranks' shares at this rank's rows.
  return distributed ? segments_.sum_mine(v) : segments_.mine(v);
}

std::vector<int> WallOperator::density_nodes() const {
  const int n = elements_->num_nodes();
  if (!near_and_real_) {
    std::vector<int> all(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
    return all;
  }
  std::vector<char> read(static_cast<std::size_t>(n), 0);
  for (int i : near_and_real_->nodes_read()) read[static_cast<std::size_t>(i)] = 1;
  const SpmeStencils::SpreadingMatrix& spreading = *node_spreading_;
  for (Eigen::Index k = 0; k < spreading.outerSize(); ++k)
    for (SpmeStencils::SpreadingMatrix::InnerIterator it(spreading, k); it; ++it) read[static_cast<std::size_t>(it.col())] = 1;
  if (!near_.coincident.empty() && (!ewald_->smooth().grid().distributed() || ranks_.root())) {
    const Eigen::SparseMatrix<double, Eigen::RowMajor> map = elements_->density_map();
    for (const auto& [t, q] : near_.coincident)
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(map, q); it; ++it)
        read[static_cast<std::size_t>(it.col())] = 1;
  }
  std::vector<int> nodes;
  for (int i = 0; i < n; ++i)
    if (read[static_cast<std::size_t>(i)]) nodes.push_back(i);
  return nodes;
}

void WallOperator::report_memory(MemoryReport& report, const std::string& prefix) const {
  report.add(prefix + ": near field", matrix_bytes(near_.correction) + matrix_bytes(near_.local) +
                                          heap_bytes(near_.coincident) + matrix_bytes(targets_));
  if (near_and_real_) {
    report.add(prefix + ": assembled real space", near_and_real_->memory_bytes() + matrix_bytes(*node_spreading_));
  }
  if (ewald_) ewald_->report_memory(report, prefix + " Ewald");
}

}  // namespace rbcflow
