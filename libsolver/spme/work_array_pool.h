#pragma once
// The grid arrays of SPME products (SpmeGrid::work_array: three grids and one, a gigabyte and a
// third at a thousand cells, for each double-layer product), kept from one product to the next
// while a solve runs instead of freed and allocated again. A run that returns its freed memory
// to the system (libsolver/stepper/step_memory.h) otherwise maps each product's arrays afresh
// and the kernel faults them in page by page, zeroed: at 125 cells 2.6 million page faults and
// 4 s of system time in a step of 27 s of CPU time (docs/performance.md, "Freed pages kept
// between products"). Products write every point of an array they use (spreading zeroes it
// first), so a kept array changes no result.
//
// While keeping(), an array given back waits for the next take(); take() hands out the smallest
// waiting array that is large enough and, when none is, frees the waiting ones (all too small)
// before it allocates. So the arrays a pool holds are those of the largest set of arrays live
// at once, not one set per grid. Not keeping, give_back() frees. Thread-safe.
#include <fftw3.h>

#include <cstddef>
#include <mutex>
#include <vector>

#include "geometry/sph/fftw_util.h"

namespace rbcflow {

class WorkArrayPool {
 public:
  // An array of at least `size` complex numbers (uninitialised).
  FftwBuffer<fftw_complex> take(std::size_t size);
  void give_back(FftwBuffer<fftw_complex> array);
  // Off frees the waiting arrays.
  void keep(bool on);
  bool keeping() const;
  std::size_t waiting_bytes() const;

 private:
  mutable std::mutex mutex_;
  bool keeping_ = false;
  std::vector<FftwBuffer<fftw_complex>> waiting_;
};

// A work array, given back to its pool when it goes (freed when it has none). Move-only.
class WorkArray {
 public:
  WorkArray(FftwBuffer<fftw_complex> array, WorkArrayPool* pool) : array_(std::move(array)), pool_(pool) {}
  WorkArray(WorkArray&& o) noexcept = default;
  WorkArray& operator=(WorkArray&&) = delete;
  ~WorkArray() {
    if (pool_ && array_.data()) pool_->give_back(std::move(array_));
  }
  fftw_complex* data() { return array_.data(); }

 private:
  FftwBuffer<fftw_complex> array_;
  WorkArrayPool* pool_;
};

}  // namespace rbcflow
