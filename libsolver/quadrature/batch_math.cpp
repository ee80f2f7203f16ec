// This file alone is compiled with -ffast-math (libsolver/quadrature/CMakeLists.txt): with it
// glibc's <math.h> declares the SIMD variants of atan2, acos and exp (bits/math-vector.h), so
// the loops below vectorise into libmvec calls. What else the flag permits touches only the
// loops' own arithmetic, at the level of rounding; the arguments are finite (the mask's is
// clamped before its division, its end values selected afterwards). The clamps are written as
// comparisons: std::clamp's reference result kept GCC 12 from vectorising the loop.
#include "batch_math.h"

#include <cmath>

namespace rbcflow {

void batch_atan2(const double* y, const double* x, double* out, std::size_t n) {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) out[i] = std::atan2(y[i], x[i]);
}

void batch_acos(const double* x, double* out, std::size_t n) {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) out[i] = std::acos(x[i] < -1.0 ? -1.0 : (x[i] > 1.0 ? 1.0 : x[i]));
}

void batch_patch_mask(const double* rho, double rho1, double* eta, std::size_t n) {
#pragma omp simd
  for (std::size_t i = 0; i < n; ++i) {
    const double t = rho[i] / rho1;
    // Below t = 1e-3, exp(-1/t) < e^{-1000} underflows to 0 and eta to exactly 1, as unclamped.
    const double tc = t >= 1.0 ? 0.5 : (t < 1e-3 ? 1e-3 : t);
    const double value = std::exp(2.0 * std::exp(-1.0 / tc) / (tc - 1.0));
    eta[i] = t <= 0.0 ? 1.0 : (t >= 1.0 ? 0.0 : value);
  }
}

}  // namespace rbcflow
