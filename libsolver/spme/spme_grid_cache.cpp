#include "spme_grid_cache.h"

namespace rbcflow {

std::shared_ptr<const SpmeGrid> SpmeGridCache::grid(EwaldKernel kernel, double tolerance, const PeriodicBox& box,
                                                    long n_sources, long n_targets, const RealSpaceUse& real_space,
                                                    const Communicator& ranks) {
  const std::lock_guard<std::mutex> lock(mutex_);
  for (const Entry& e : entries_) {
    if (e.kernel == kernel && e.tolerance == tolerance && e.lengths == box.lengths() && e.n_sources == n_sources &&
        e.n_targets == n_targets && e.real_space.weight == real_space.weight &&
        e.real_space.max_pairs == real_space.max_pairs && e.ranks == ranks.size())
      return e.grid;
  }
  const EwaldParameters p = choose_ewald_parameters(kernel, tolerance, box, n_sources, n_targets, real_space).parameters;
  const double points = static_cast<double>(p.grid[0]) * p.grid[1] * p.grid[2];
  auto grid = std::make_shared<const SpmeGrid>(
      box, p, points >= static_cast<double>(kMeasuredGridPoints) ? FftPlanning::measure : FftPlanning::estimate, ranks,
      work_arrays_);
  entries_.push_back({kernel, tolerance, box.lengths(), n_sources, n_targets, real_space, ranks.size(), grid});
  return grid;
}

std::shared_ptr<const SpmeGrid> ewald_grid(SpmeGridCache* cache, EwaldKernel kernel, double tolerance,
                                           const PeriodicBox& box, long n_sources, long n_targets,
                                           const RealSpaceUse& real_space, const Communicator& ranks) {
  if (cache) return cache->grid(kernel, tolerance, box, n_sources, n_targets, real_space, ranks);
  const EwaldChoice choice =
      choose_ewald_parameters(kernel, tolerance, box, n_sources, n_targets, real_space);
  return std::make_shared<const SpmeGrid>(box, choice.parameters, FftPlanning::estimate, ranks);
}

std::size_t SpmeGridCache::memory_bytes() const {
  const std::lock_guard lock(mutex_);
  std::size_t bytes = 0;
  for (const Entry& e : entries_) bytes += e.grid->memory_bytes();
  return bytes;
}

}  // namespace rbcflow
