#pragma once
// The largest grid array of SPME products (SpmeGrid::work_array: the three grids of a
// double-layer product, a gigabyte at a thousand cells), kept from one product to the next
// while a solve runs instead of freed and allocated again. A run that returns its freed memory
// to the system (libsolver/stepper/step_memory.h) otherwise maps each product's arrays afresh
// and the kernel faults them in page by page, zeroed (docs/performance.md, "Freed pages kept
// between products and builds"). Products write every point of an array they use (spreading
// zeroes it first), so a kept array changes no result.
//
// One array waits at a time, the largest given back: it stays live between products, where the
// other arrays of a product (the lean double layer's one grid, a third of it) are not, so that
// what the step holds at its peak grows by less than the arrays a product adds. take() hands
// out the waiting array when it is large enough and otherwise frees it and allocates. Not
// keeping(), give_back() frees. Thread-safe.
#include <fftw3.h>

#include <cstddef>
#include <mutex>

#include "geometry/sph/fftw_util.h"

namespace rbcflow {

class WorkArrayPool {
 public:
  // An array of at least `size` complex numbers (uninitialised).
  FftwBuffer<fftw_complex> take(std::size_t size);
  void give_back(FftwBuffer<fftw_complex> array);
  // Off frees the waiting array.
  void keep(bool on);
  bool keeping() const;
  std::size_t waiting_bytes() const;

 private:
  mutable std::mutex mutex_;
  bool keeping_ = false;
  FftwBuffer<fftw_complex> waiting_;
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
