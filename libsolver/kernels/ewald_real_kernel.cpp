#include "ewald_real_kernel.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace rbcflow {
namespace {

// Chebyshev interpolant of erfcx(x) = exp(x^2) erfc(x) at n nodes on each interval, converted
// to monomials in the local coordinate t in [-1, 1].
std::vector<double> erfcx_table(int intervals, int per_unit, int n) {
  // Monomial coefficients of T_0 .. T_{n-1}.
  std::vector<std::vector<double>> T(n, std::vector<double>(n, 0.0));
  T[0][0] = 1.0;
  if (n > 1) T[1][1] = 1.0;
  for (int k = 2; k < n; ++k)
    for (int j = 0; j < n; ++j) T[k][j] = (j > 0 ? 2.0 * T[k - 1][j - 1] : 0.0) - T[k - 2][j];
  std::vector<double> table(static_cast<std::size_t>(intervals) * n, 0.0);
  for (int i = 0; i < intervals; ++i) {
    const double mid = (i + 0.5) / per_unit, half = 0.5 / per_unit;
    std::vector<double> f(n), node(n);
    for (int j = 0; j < n; ++j) {
      node[j] = std::cos(std::numbers::pi * (j + 0.5) / n);
      const double x = mid + half * node[j];
      f[j] = std::exp(x * x) * std::erfc(x);
    }
    for (int k = 0; k < n; ++k) {
      double c = 0.0;
      for (int j = 0; j < n; ++j) c += f[j] * std::cos(k * std::acos(node[j]));
      c *= (k == 0 ? 1.0 : 2.0) / n;
      for (int m = 0; m < n; ++m) table[static_cast<std::size_t>(i) * n + m] += c * T[k][m];
    }
  }
  return table;
}

}  // namespace

EwaldRealKernel::EwaldRealKernel(double xi)
    : xi_(xi), two_xi_over_sqrt_pi_(2.0 * xi * std::numbers::inv_sqrtpi) {
  if (!(std::isfinite(xi) && xi > 0.0))
    throw std::invalid_argument("Ewald real-space kernel: xi must be positive, got " +
                                std::to_string(xi));
  static const std::vector<double> table =
      erfcx_table(static_cast<int>(kTableEnd) * kIntervalsPerUnit, kIntervalsPerUnit, kTerms);
  coefficients_ = table.data();
}

}  // namespace rbcflow
