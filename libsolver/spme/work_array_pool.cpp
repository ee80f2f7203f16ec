#include "work_array_pool.h"

#include <utility>

namespace rbcflow {

FftwBuffer<fftw_complex> WorkArrayPool::take(std::size_t size) {
  FftwBuffer<fftw_complex> waiting;
  {
    const std::lock_guard lock(mutex_);
    std::swap(waiting, waiting_);
  }
  if (waiting.size() >= size) return waiting;
  waiting = FftwBuffer<fftw_complex>();  // freed before the new one is allocated
  return FftwBuffer<fftw_complex>(size);
}

void WorkArrayPool::give_back(FftwBuffer<fftw_complex> array) {
  const std::lock_guard lock(mutex_);
  if (keeping_ && array.size() > waiting_.size()) std::swap(array, waiting_);
  // `array` (the smaller of the two) is freed on return
}

void WorkArrayPool::keep(bool on) {
  FftwBuffer<fftw_complex> freed;
  const std::lock_guard lock(mutex_);
  keeping_ = on;
  if (!on) std::swap(freed, waiting_);
}

bool WorkArrayPool::keeping() const {
  const std::lock_guard lock(mutex_);
  return keeping_;
}

std::size_t WorkArrayPool::waiting_bytes() const {
  const std::lock_guard lock(mutex_);
  return waiting_.size() * sizeof(fftw_complex);
}

}  // namespace rbcflow
