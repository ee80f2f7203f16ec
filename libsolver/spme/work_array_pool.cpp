#include "work_array_pool.h"

#include <algorithm>
#include <utility>

namespace rbcflow {

FftwBuffer<fftw_complex> WorkArrayPool::take(std::size_t size) {
  std::vector<FftwBuffer<fftw_complex>> too_small;  // freed outside the lock
  {
    const std::lock_guard lock(mutex_);
    auto best = waiting_.end();
    for (auto a = waiting_.begin(); a != waiting_.end(); ++a)
      if (a->size() >= size && (best == waiting_.end() || a->size() < best->size())) best = a;
    if (best != waiting_.end()) {
      FftwBuffer<fftw_complex> array = std::move(*best);
      waiting_.erase(best);
      return array;
    }
    too_small.swap(waiting_);
  }
  too_small.clear();
  return FftwBuffer<fftw_complex>(size);
}

void WorkArrayPool::give_back(FftwBuffer<fftw_complex> array) {
  const std::lock_guard lock(mutex_);
  if (keeping_) waiting_.push_back(std::move(array));
}

void WorkArrayPool::keep(bool on) {
  std::vector<FftwBuffer<fftw_complex>> freed;
  const std::lock_guard lock(mutex_);
  keeping_ = on;
  if (!on) freed.swap(waiting_);
}

bool WorkArrayPool::keeping() const {
  const std::lock_guard lock(mutex_);
  return keeping_;
}

std::size_t WorkArrayPool::waiting_bytes() const {
  const std::lock_guard lock(mutex_);
  std::size_t bytes = 0;
  for (const FftwBuffer<fftw_complex>& a : waiting_) bytes += a.size() * sizeof(fftw_complex);
  return bytes;
}

}  // namespace rbcflow
