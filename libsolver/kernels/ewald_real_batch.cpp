// This file alone is compiled with -ffast-math (libsolver/kernels/CMakeLists.txt): with it
// glibc's <math.h> declares the SIMD variants of erfc and exp (bits/math-vector.h), so the
// loops below vectorise into libmvec calls. What else the flag permits touches only the loops'
// own arithmetic, at the level of rounding; every argument is finite and r > 0.
#include "ewald_real_batch.h"

#include <cmath>
#include <numbers>

namespace rbcflow {

void batch_stokeslet_coeffs(double xi, const double* x, const double* y, const double* z, int n, double* a,
                            double* b) {
  const double two_xi_over_sqrt_pi = 2.0 * xi * std::numbers::inv_sqrtpi, xi2 = xi * xi;
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const double r2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i], r = std::sqrt(r2), inv_r = 1.0 / r;
    const double erfc_over_r = std::erfc(xi * r) * inv_r, gauss = two_xi_over_sqrt_pi * std::exp(-xi2 * r2);
    a[i] = erfc_over_r - gauss;
    b[i] = (erfc_over_r + gauss) * inv_r * inv_r;
  }
}

void batch_stresslet_coeffs(double xi, const double* x, const double* y, const double* z, int n, double* alpha,
                            double* beta) {
  const double xi_over_sqrt_pi = xi * std::numbers::inv_sqrtpi, xi2 = xi * xi;
#pragma omp simd
  for (int i = 0; i < n; ++i) {
    const double r2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i], r = std::sqrt(r2), inv_r2 = 1.0 / r2;
    const double h = xi_over_sqrt_pi * std::exp(-xi2 * r2);  // xi e^{-xi^2 r^2} / sqrt(pi)
    alpha[i] = -6.0 * std::erfc(xi * r) * inv_r2 * inv_r2 / r - (12.0 * inv_r2 + 8.0 * xi2) * inv_r2 * h;
    beta[i] = 4.0 * xi2 * h;
  }
}

}  // namespace rbcflow
