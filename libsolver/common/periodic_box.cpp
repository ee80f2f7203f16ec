#include "libsolver/common/periodic_box.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace rbcflow {

PeriodicBox::PeriodicBox(const Eigen::Vector3d& lengths) : lengths_(lengths) {
  for (int d = 0; d < 3; ++d) {
    if (!(std::isfinite(lengths[d]) && lengths[d] > 0.0)) {
      std::ostringstream msg;
      msg << "periodic box: side lengths must be positive and finite, got (" << lengths[0] << ", "
          << lengths[1] << ", " << lengths[2] << ")";
      throw std::invalid_argument(msg.str());
    }
  }
}

Eigen::Vector3d PeriodicBox::wrap(const Eigen::Vector3d& x) const {
  Eigen::Vector3d w;
  for (int d = 0; d < 3; ++d) {
    w[d] = x[d] - lengths_[d] * std::floor(x[d] / lengths_[d]);
    if (w[d] >= lengths_[d]) w[d] = 0.0;  // x slightly below a multiple of L rounds up to L
  }
  return w;
}

}  // namespace rbcflow
