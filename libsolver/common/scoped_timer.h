#pragma once
// Wall-clock timing of a scope, for the stage timings of a step (stepper/step_timings.h).
#include <chrono>

namespace rbcflow {

// Adds the seconds between construction and destruction (or stop()) to `sink`.
class ScopedTimer {
 public:
  explicit ScopedTimer(double& sink) : sink_(&sink), start_(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() { stop(); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;
  void stop() {
    if (!sink_) return;
    *sink_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    sink_ = nullptr;
  }

 private:
  double* sink_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace rbcflow
