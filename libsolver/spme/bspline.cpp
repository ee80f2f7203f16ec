#include "bspline.h"

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rbcflow {

void check_spline_order(int order) {
  if (order < kMinSplineOrder || order > kMaxSplineOrder) {
    throw std::invalid_argument("SPME: B-spline order must be between " +
                                std::to_string(kMinSplineOrder) + " and " +
                                std::to_string(kMaxSplineOrder) + ", got " + std::to_string(order));
  }
}

double bspline(int order, double u) {
  if (u <= 0.0 || u >= order) return 0.0;
  const double j = std::floor(u);
  double w[kMaxSplineOrder];
  bspline_weights(order, u - j, w);
  return w[static_cast<int>(j)];
}

void bspline_weights(int order, double t, double* w) {
  // w holds M_n(t + j), j = 0 .. n-1, raised from n = 1 to n = order in place (j descending
  // so that w[j - 1] is still M_{n-1}).
  w[0] = 1.0;
  for (int n = 2; n <= order; ++n) {
    const double inv = 1.0 / (n - 1);
    w[n - 1] = (n - (t + n - 1)) * w[n - 2] * inv;
    for (int j = n - 2; j >= 1; --j) w[j] = ((t + j) * w[j] + (n - t - j) * w[j - 1]) * inv;
    w[0] = t * w[0] * inv;
  }
}

std::vector<double> bspline_modulus(int order, int grid_size) {
  std::vector<double> m_at_integers(order - 1);
  for (int j = 0; j < order - 1; ++j) m_at_integers[j] = bspline(order, j + 1.0);
  std::vector<double> modulus(grid_size);
  for (int m = 0; m < grid_size; ++m) {
    std::complex<double> s = 0.0;
    for (int j = 0; j < order - 1; ++j)
      s += m_at_integers[j] * std::polar(1.0, 2.0 * std::numbers::pi * m * j / grid_size);
    modulus[m] = std::norm(s);
  }
  return modulus;
}

}  // namespace rbcflow
