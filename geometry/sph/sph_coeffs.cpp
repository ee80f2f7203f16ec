#include "geometry/sph/sph_coeffs.h"

#include <algorithm>
#include <stdexcept>

namespace rbcflow {

SHCoeffs::SHCoeffs(int order, int components) : order_(order) {
  if (order < 1) throw std::invalid_argument("SHCoeffs: order must be >= 1");
  if (components < 1) throw std::invalid_argument("SHCoeffs: components must be >= 1");
  values_.setZero(static_cast<Eigen::Index>(order) * order, components);
}

SHCoeffs SHCoeffs::resampled(int new_order) const {
  SHCoeffs out(new_order, components());
  const int common = std::min(order_, new_order);
  for (int m = 0; m < common; ++m) {
    const int len = common - m;
    out.values_.middleRows(cos_offset(new_order, m), len) =
        values_.middleRows(cos_offset(order_, m), len);
    if (m > 0) {
      out.values_.middleRows(sin_offset(new_order, m), len) =
          values_.middleRows(sin_offset(order_, m), len);
    }
  }
  return out;
}

Eigen::VectorXd SHCoeffs::spectrum() const {
  Eigen::VectorXd e = Eigen::VectorXd::Zero(order_);
  for (int m = 0; m < order_; ++m) {
    for (int n = m; n < order_; ++n) {
      e[n] += values_.row(cos_index(n, m)).squaredNorm();
      if (m > 0) e[n] += values_.row(sin_index(n, m)).squaredNorm();
    }
  }
  return e;
}

}  // namespace rbcflow
