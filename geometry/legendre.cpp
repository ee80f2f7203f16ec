#include "legendre.h"

#include <cmath>
#include <stdexcept>

namespace rbcflow {

LegendreTables legendre_theta_tables(const Eigen::VectorXd& theta, int L, int max_derivative) {
  if (L < 1) throw std::invalid_argument("legendre_theta_tables: order must be >= 1");
  if (max_derivative < 0) throw std::invalid_argument("legendre_theta_tables: negative derivative");
  const Eigen::Index nt = theta.size();
  LegendreTables tables(max_derivative + 1, std::vector<Eigen::MatrixXd>(L));

  auto& p = tables[0];
  for (int m = 0; m < L; ++m) p[m].setZero(nt, L - m);
  for (Eigen::Index i = 0; i < nt; ++i) {
    const double x = std::cos(theta[i]);
    const double s = std::sin(theta[i]);
    double pmm = 1.0 / std::sqrt(2.0);  // Pbar_0^0
    for (int m = 0; m < L; ++m) {
      if (m > 0) pmm *= std::sqrt((2.0 * m + 1.0) / (2.0 * m)) * s;
      p[m](i, 0) = pmm;
      if (m + 1 >= L) continue;
      p[m](i, 1) = std::sqrt(2.0 * m + 3.0) * x * pmm;
      for (int n = m + 2; n < L; ++n) {
        const double a = std::sqrt((4.0 * n * n - 1.0) / (double(n) * n - double(m) * m));
        const double b = std::sqrt((double(n - 1) * (n - 1) - double(m) * m) /
                                   (4.0 * (n - 1) * (n - 1) - 1.0));
        p[m](i, n - m) = a * (x * p[m](i, n - m - 1) - b * p[m](i, n - m - 2));
      }
    }
  }

  for (int k = 1; k <= max_derivative; ++k) {
    const auto& prev = tables[k - 1];
    auto& cur = tables[k];
    for (int m = 0; m < L; ++m) {
      cur[m].setZero(nt, L - m);
      for (int n = m; n < L; ++n) {
        const double c_down = std::sqrt(double(n + m) * (n - m + 1));
        const double c_up = std::sqrt(double(n - m) * (n + m + 1));
        auto col = cur[m].col(n - m);
        // Pbar_n^{m-1}: for m = 0 use Pbar_n^{-1} = -Pbar_n^1 (absent when n = 0).
        if (m > 0) {
          col += (0.5 * c_down) * prev[m - 1].col(n - (m - 1));
        } else if (n >= 1) {
          col -= (0.5 * c_down) * prev[1].col(n - 1);
        }
        if (n >= m + 1) col -= (0.5 * c_up) * prev[m + 1].col(n - (m + 1));
      }
    }
  }
  return tables;
}

}  // namespace rbcflow
