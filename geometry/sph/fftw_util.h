#pragma once
// Small FFTW helpers shared by every module that plans transforms: FFTW's planner is not
// thread-safe (execution is), and new-array execution needs SIMD-aligned arrays.
#include <fftw3.h>

#include <cstddef>
#include <mutex>
#include <utility>

namespace rbcflow {

// Every fftw_plan_* and fftw_destroy_plan call must hold this lock.
std::mutex& fftw_planner_mutex();

// A growable array allocated with fftw_malloc (aligned as FFTW's SIMD codelets require).
template <typename T>
class FftwBuffer {
 public:
  FftwBuffer() = default;
  explicit FftwBuffer(std::size_t n) { resize(n); }
  FftwBuffer(const FftwBuffer&) = delete;
  FftwBuffer& operator=(const FftwBuffer&) = delete;
  FftwBuffer(FftwBuffer&& o) noexcept : data_(std::exchange(o.data_, nullptr)), size_(std::exchange(o.size_, 0)) {}
  FftwBuffer& operator=(FftwBuffer&& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    return *this;
  }
  ~FftwBuffer() { fftw_free(data_); }

  // Grows (never shrinks) to hold at least n elements; contents are not preserved.
  void reserve(std::size_t n) {
    if (n <= size_) return;
    fftw_free(data_);
    data_ = static_cast<T*>(fftw_malloc(n * sizeof(T)));
    if (!data_) throw std::bad_alloc();
    size_ = n;
  }
  void resize(std::size_t n) { reserve(n); }
  T* data() { return data_; }
  std::size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  std::size_t size_ = 0;
};

}  // namespace rbcflow
