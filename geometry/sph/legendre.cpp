#include "geometry/sph/legendre.h"

#include <cmath>
#include <stdexcept>
#include <unordered_map>

namespace rbcflow {
namespace {

// Coefficients of the recurrences of legendre_theta_point, per packed (n, m).
struct LegendreRecurrence {
  std::vector<double> a, b;      // Pbar_n^m = a (x Pbar_{n-1}^m - b Pbar_{n-2}^m), n >= m + 2
  std::vector<double> down, up;  // derivative: down Pbar_n^{m-1} - up Pbar_n^{m+1}
  std::vector<double> diag, first;  // per m: Pbar_m^m = diag Pbar_{m-1}^{m-1} sin, Pbar_{m+1}^m = first x Pbar_m^m
};

const LegendreRecurrence& legendre_recurrence(int L) {
  thread_local std::unordered_map<int, LegendreRecurrence> cache;
  auto [it, inserted] = cache.try_emplace(L);
  LegendreRecurrence& r = it->second;
  if (!inserted) return r;
  const int size = legendre_size(L);
  r.a.assign(size, 0.0);
  r.b.assign(size, 0.0);
  r.down.assign(size, 0.0);
  r.up.assign(size, 0.0);
  r.diag.assign(L, 0.0);
  r.first.assign(L, 0.0);
  for (int m = 0; m < L; ++m) {
    if (m > 0) r.diag[m] = std::sqrt((2.0 * m + 1.0) / (2.0 * m));
    r.first[m] = std::sqrt(2.0 * m + 3.0);
    for (int n = m; n < L; ++n) {
      const int i = legendre_index(L, n, m);
      if (n >= m + 2) {
        r.a[i] = std::sqrt((4.0 * n * n - 1.0) / (double(n) * n - double(m) * m));
        r.b[i] = std::sqrt((double(n - 1) * (n - 1) - double(m) * m) / (4.0 * (n - 1) * (n - 1) - 1.0));
      }
      r.down[i] = 0.5 * std::sqrt(double(n + m) * (n - m + 1));
      r.up[i] = 0.5 * std::sqrt(double(n - m) * (n + m + 1));
    }
  }
  return r;
}

}  // namespace

void legendre_theta_point(double theta, int L, int max_derivative, double* p) {
  if (L < 1) throw std::invalid_argument("legendre_theta_point: order must be >= 1");
  if (max_derivative < 0) throw std::invalid_argument("legendre_theta_point: negative derivative");
  const LegendreRecurrence& r = legendre_recurrence(L);
  const double x = std::cos(theta), s = std::sin(theta);
  double pmm = 1.0 / std::sqrt(2.0);  // Pbar_0^0
  for (int m = 0; m < L; ++m) {
    const int i0 = legendre_index(L, m, m);
    if (m > 0) pmm *= r.diag[m] * s;
    p[i0] = pmm;
    if (m + 1 >= L) continue;
    p[i0 + 1] = r.first[m] * x * pmm;
    for (int i = i0 + 2; i < i0 + L - m; ++i) p[i] = r.a[i] * (x * p[i - 1] - r.b[i] * p[i - 2]);
  }
  const int size = legendre_size(L);
  for (int k = 1; k <= max_derivative; ++k) {
    const double* prev = p + (k - 1) * size;
    double* cur = p + k * size;
    for (int m = 0; m < L; ++m) {
      for (int n = m; n < L; ++n) {
        const int i = legendre_index(L, n, m);
        double v = 0.0;
        if (m > 0) {
          v += r.down[i] * prev[legendre_index(L, n, m - 1)];
        } else if (n >= 1) {
          v -= r.down[i] * prev[legendre_index(L, n, 1)];
        }
        if (n >= m + 1) v -= r.up[i] * prev[legendre_index(L, n, m + 1)];
        cur[i] = v;
      }
    }
  }
}

LegendreTables legendre_theta_tables(const Eigen::VectorXd& theta, int L, int max_derivative) {
  if (L < 1) throw std::invalid_argument("legendre_theta_tables: order must be >= 1");
  if (max_derivative < 0) throw std::invalid_argument("legendre_theta_tables: negative derivative");
  const Eigen::Index nt = theta.size();
  const int size = legendre_size(L);
  LegendreTables tables(max_derivative + 1, std::vector<Eigen::MatrixXd>(L));
  for (auto& table : tables) {
    for (int m = 0; m < L; ++m) table[m].resize(nt, L - m);
  }
  std::vector<double> p(std::size_t(max_derivative + 1) * size);
  for (Eigen::Index i = 0; i < nt; ++i) {
    legendre_theta_point(theta[i], L, max_derivative, p.data());
    for (int k = 0; k <= max_derivative; ++k) {
      for (int m = 0; m < L; ++m) {
        for (int n = m; n < L; ++n) tables[k][m](i, n - m) = p[k * size + legendre_index(L, n, m)];
      }
    }
  }
  return tables;
}

}  // namespace rbcflow
