#include "ewald_plan.h"

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "real_space_sum.h"

namespace rbcflow {
namespace {

double seconds_between(std::chrono::steady_clock::time_point a,
                       std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

std::vector<double>* EwaldPlan::kept(std::vector<double>& coefficients) const {
  return neighbors().n_pairs() <= max_kept_pairs_ ? &coefficients : nullptr;
}

const NeighborList& EwaldPlan::neighbors() const {
  if (!neighbors_) throw std::logic_error("EwaldPlan: the real-space sum was released (release_real_space)");
  return *neighbors_;
}

EwaldPlan::EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources,
                     const PointField& targets, PairShares shares)
    : neighbors_(std::in_place, grid->box(), grid->parameters().cutoff, sources, targets),
      smooth_(std::move(grid), sources, targets),
      shares_(std::move(shares)) {}

EwaldPlan::EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& points, PairShares shares)
    : neighbors_(std::in_place, grid->box(), grid->parameters().cutoff, points, points),
      smooth_(std::move(grid), points),
      shares_(std::move(shares)) {}

namespace {

// SourceRows or TargetRows of `points`.
template <typename Rows>
PointField rows_of(const PointField& points, Rows rows) {
  return points.middleRows(rows.begin, rows.end - rows.begin);
}

// The rows, or std::invalid_argument when they are not rows of n sources (targets).
template <typename Rows>
Rows checked(Rows rows, Eigen::Index n) {
  if (rows.begin < 0 || rows.end < rows.begin || rows.end > n) {
    const char* what = std::is_same_v<Rows, SourceRows> ? "source" : "target";
    throw std::invalid_argument(std::string("EwaldPlan: ") + what + " rows [" + std::to_string(rows.begin) + ", " +
                                std::to_string(rows.end) + ") of " + std::to_string(n));
  }
  return rows;
}

SpmePlan smooth_plan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources, const PointField& targets,
                     SourceRows rows) {
  if (!grid->distributed()) return SpmePlan(std::move(grid), rows_of(sources, rows), targets);
  if (&sources == &targets) return SpmePlan(std::move(grid), sources);
  return SpmePlan(std::move(grid), sources, targets);
}

}  // namespace

EwaldPlan::EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources, const PointField& targets,
                     SourceRows rows, PairShares shares)
    : rows_(checked(rows, sources.rows()).begin == 0 && rows.end == sources.rows() ? std::nullopt
                                                                                     : std::optional<SourceRows>(rows)),
      smooth_of_rows_(rows_ && !grid->distributed()),
      smooth_(smooth_plan(grid, sources, targets, rows)),
      shares_(std::move(shares)) {
  if (has_real_space_sources())
    neighbors_.emplace(grid->box(), grid->parameters().cutoff, rows_of(sources, rows), targets);
}

EwaldPlan::EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources, const PointField& targets,
                     TargetRows rows)
    : target_rows_(checked(rows, targets.rows())),
      n_targets_(targets.rows()),
      smooth_at_rows_(!grid->distributed()),
      smooth_(grid->distributed() ? SpmePlan(grid, sources, targets) : SpmePlan(grid, sources, rows_of(targets, rows))) {
  if (has_real_space_sources())
    neighbors_.emplace(grid->box(), grid->parameters().cutoff, sources, rows_of(targets, rows));
}

std::vector<Eigen::Index> EwaldPlan::density_rows() const {
  std::vector<Eigen::Index> rows;
  if (!rows_) {
    rows.resize(static_cast<std::size_t>(smooth_.n_sources()));
    std::iota(rows.begin(), rows.end(), Eigen::Index{0});
    return rows;
  }
  for (Eigen::Index i = rows_->begin; i < rows_->end; ++i) rows.push_back(i);
  if (!smooth_of_rows_) {
    for (const int i : smooth_.sources().point_indices()) rows.push_back(i);
    std::sort(rows.begin(), rows.end());
    rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  }
  return rows;
}

void EwaldPlan::add_at_rows(PointField& u, const PointField& at_rows) const {
  if (target_rows_) {
    u.middleRows(target_rows_->begin, target_rows_->end - target_rows_->begin) += at_rows;
  } else {
    u += at_rows;
  }
}

PointField EwaldPlan::smooth_at_every_target(PointField smooth) const {
  if (!smooth_at_rows_) return smooth;
  PointField u = PointField::Zero(n_targets_, 3);
  add_at_rows(u, smooth);
  return u;
}

const PointField& EwaldPlan::real_space_rows(const PointField& density, PointField& copy) const {
  return rows_ ? (copy = rows_of(density, *rows_)) : density;
}

const PointField& EwaldPlan::smooth_rows(const PointField& density, PointField& copy) const {
  return smooth_of_rows_ ? (copy = rows_of(density, *rows_)) : density;
}

PointField EwaldPlan::single_layer(const PointField& forces) {
  PointField copy;
  PointField u = smooth_at_every_target(smooth_.single_layer(smooth_rows(forces, copy)));
  const auto start = std::chrono::steady_clock::now();
  if (has_real_space_sources()) {
    add_at_rows(u, real_space_single_layer(neighbors(), xi(), real_space_rows(forces, copy), kept(single_coefficients_),
                                           &shares_));
  }
  timings_.real_space = seconds_between(start, std::chrono::steady_clock::now());
  timings_.smooth = smooth_.timings();
  return u;
}

PointField EwaldPlan::smooth_single_layer(const PointField& forces) {
  PointField copy;
  PointField u = smooth_at_every_target(smooth_.single_layer(smooth_rows(forces, copy)));
  timings_.real_space = 0.0;
  timings_.smooth = smooth_.timings();
  return u;
}

PointField EwaldPlan::smooth_single_layer(const SpmeStencils::SpreadingMatrix& spreading, const PointField& x) {
  PointField u = smooth_at_every_target(smooth_.single_layer(spreading, x));
  timings_.real_space = 0.0;
  timings_.smooth = smooth_.timings();
  return u;
}

PointField EwaldPlan::double_layer(const PointField& q, const PointField& normals) {
  double_products_ = true;
  PointField q_copy, n_copy;
  PointField u = smooth_at_every_target(smooth_.double_layer(smooth_rows(q, q_copy), smooth_rows(normals, n_copy)));
  const auto start = std::chrono::steady_clock::now();
  if (has_real_space_sources()) {
    add_at_rows(u, real_space_double_layer(neighbors(), xi(), real_space_rows(q, q_copy),
                                           real_space_rows(normals, n_copy), kept(double_coefficients_), &shares_));
  }
  timings_.real_space = seconds_between(start, std::chrono::steady_clock::now());
  timings_.smooth = smooth_.timings();
  return u;
}

void EwaldPlan::report_memory(MemoryReport& report, const std::string& prefix) const {
  if (neighbors_) report.add(prefix + ": neighbour list", neighbors_->memory_bytes());
  report.add(prefix + ": kept pair coefficients", heap_bytes(single_coefficients_) + heap_bytes(double_coefficients_));
  report.add(prefix + ": B-spline stencils", smooth_.stencil_bytes());
  report.add(prefix + ": pair shares", shares_.memory_bytes());
  // Work arrays live for one product, and products run one at a time: the largest counts.
  report.add_max("SPME work arrays (one product at a time)", smooth_.work_bytes(double_products_ ? 6 : 3));
}

}  // namespace rbcflow
