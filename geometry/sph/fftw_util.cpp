#include "geometry/sph/fftw_util.h"

namespace rbcflow {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace rbcflow
