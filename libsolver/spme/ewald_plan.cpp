#include "ewald_plan.h"

#include <chrono>
#include <cstdint>

#include "real_space_sum.h"

namespace rbcflow {
namespace {

double seconds_between(std::chrono::steady_clock::time_point a,
                       std::chrono::steady_clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace

std::vector<double>* EwaldPlan::kept(std::vector<double>& coefficients) const {
  return neighbors_.n_pairs() <= kMaxKeptPairs ? &coefficients : nullptr;
}

EwaldPlan::EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& sources,
                     const PointField& targets, PairShares shares)
    : neighbors_(grid->box(), grid->parameters().cutoff, sources, targets),
      smooth_(std::move(grid), sources, targets),
      shares_(std::move(shares)) {}

EwaldPlan::EwaldPlan(std::shared_ptr<const SpmeGrid> grid, const PointField& points, PairShares shares)
    : neighbors_(grid->box(), grid->parameters().cutoff, points, points),
      smooth_(std::move(grid), points),
      shares_(std::move(shares)) {}

PointField EwaldPlan::single_layer(const PointField& forces) {
  PointField u = smooth_.single_layer(forces);
  const auto start = std::chrono::steady_clock::now();
  u += real_space_single_layer(neighbors_, xi(), forces, kept(single_coefficients_), &shares_);
  timings_.real_space = seconds_between(start, std::chrono::steady_clock::now());
  timings_.smooth = smooth_.timings();
  return u;
}

PointField EwaldPlan::smooth_single_layer(const PointField& forces) {
  PointField u = smooth_.single_layer(forces);
  timings_.real_space = 0.0;
  timings_.smooth = smooth_.timings();
  return u;
}

PointField EwaldPlan::smooth_single_layer(const SpmeStencils::SpreadingMatrix& spreading, const PointField& x) {
  PointField u = smooth_.single_layer(spreading, x);
  timings_.real_space = 0.0;
  timings_.smooth = smooth_.timings();
  return u;
}

PointField EwaldPlan::double_layer(const PointField& q, const PointField& normals) {
  PointField u = smooth_.double_layer(q, normals);
  const auto start = std::chrono::steady_clock::now();
  u += real_space_double_layer(neighbors_, xi(), q, normals, kept(double_coefficients_), &shares_);
  timings_.real_space = seconds_between(start, std::chrono::steady_clock::now());
  timings_.smooth = smooth_.timings();
  return u;
}

}  // namespace rbcflow
