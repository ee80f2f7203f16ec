#pragma once
// Ewald parameters and SPME grids (FFTW plans, influence function) kept from one time step to
// the next: the choice depends only on the kernel, the tolerance, the box and the point counts
// (ewald_parameters.h), which stay the same for a whole run, so each grid of a run is chosen and
// built once instead of at every step. A cached grid is the grid a fresh build would give, with
// FFTW_MEASURE plans from kMeasuredGridPoints up: their planning (seconds) is paid once per run
// and every product of every step runs the faster transform. The grids take their work arrays
// from the cache's pool (work_array_pool.h), which several caches may share.
#include <memory>
#include <mutex>
#include <vector>

#include "ewald_parameters.h"
#include "spme_grid.h"
#include "work_array_pool.h"

namespace rbcflow {

// 64^3: below it a transform takes milliseconds and FFTW_ESTIMATE's plans lose little.
inline constexpr std::size_t kMeasuredGridPoints = std::size_t{1} << 18;

class SpmeGridCache {
 public:
  explicit SpmeGridCache(std::shared_ptr<WorkArrayPool> work_arrays = std::make_shared<WorkArrayPool>())
      : work_arrays_(std::move(work_arrays)) {}

  // The grid of choose_ewald_parameters(kernel, tolerance, box, n_sources, n_targets,
  // real_space), split over `ranks` where it can be (spme_grid.h). Thread-safe; with several
  // ranks, collective: every rank asks for the same grids in the same order.
  std::shared_ptr<const SpmeGrid> grid(EwaldKernel kernel, double tolerance, const PeriodicBox& box, long n_sources,
                                       long n_targets = -1, const RealSpaceUse& real_space = {},
                                       const Communicator& ranks = {});
  std::size_t memory_bytes() const;  // of the grids it holds (not of their work arrays)
  WorkArrayPool& work_arrays() const { return *work_arrays_; }

 private:
  struct Entry {
    EwaldKernel kernel;
    double tolerance;
    Eigen::Vector3d lengths;
    long n_sources, n_targets;
    RealSpaceUse real_space;
    int ranks;
    std::shared_ptr<const SpmeGrid> grid;
  };
  std::shared_ptr<WorkArrayPool> work_arrays_;
  mutable std::mutex mutex_;
  std::vector<Entry> entries_;
};

// From `cache`, or built afresh (FFTW_ESTIMATE) when it is null.
std::shared_ptr<const SpmeGrid> ewald_grid(SpmeGridCache* cache, EwaldKernel kernel, double tolerance,
                                           const PeriodicBox& box, long n_sources, long n_targets = -1,
                                           const RealSpaceUse& real_space = {}, const Communicator& ranks = {});

}  // namespace rbcflow
