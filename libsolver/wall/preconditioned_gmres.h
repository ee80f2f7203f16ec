#pragma once
// Restarted GMRES (Saad & Schultz 1986) with right preconditioning: solves A M^{-1} y = b,
// x = M^{-1} y, so the residual it monitors is the true one, |b - A x| / |b|. A and M^{-1}
// are callables Eigen::VectorXd(const Eigen::VectorXd&). Modified Gram-Schmidt, Givens
// rotations; the initial guess is x.
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace rbcflow {

struct GmresReport {
  int iterations = 0;  // operator applications inside the Krylov cycles
  double relative_residual = 0.0;
  bool converged = false;
};

template <typename Operator, typename Preconditioner>
GmresReport preconditioned_gmres(Operator&& A, Preconditioner&& M_inv, const Eigen::VectorXd& b,
                                 Eigen::VectorXd& x, double tolerance, int max_iterations,
                                 int restart = 60) {
  GmresReport report;
  const double b_norm = b.norm();
  if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
  if (b_norm == 0.0) {
    x.setZero();
    report.converged = true;
    return report;
  }
  while (true) {
    const Eigen::VectorXd r = b - A(x);
    const double beta = r.norm();
    report.relative_residual = beta / b_norm;
    if (report.relative_residual <= tolerance) {
      report.converged = true;
      return report;
    }
    if (report.iterations >= max_iterations) return report;
    const int m = std::max(1, restart);
    std::vector<Eigen::VectorXd> V{r / beta};
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
    Eigen::VectorXd cs(m), sn(m), g = Eigen::VectorXd::Zero(m + 1);
    g[0] = beta;
    int k = 0;
    while (k < m && report.iterations < max_iterations) {
      Eigen::VectorXd w = A(M_inv(V[k]));
      ++report.iterations;
      for (int j = 0; j <= k; ++j) {
        H(j, k) = w.dot(V[j]);
        w -= H(j, k) * V[j];
      }
      H(k + 1, k) = w.norm();
      for (int j = 0; j < k; ++j) {
        const double t = cs[j] * H(j, k) + sn[j] * H(j + 1, k);
        H(j + 1, k) = -sn[j] * H(j, k) + cs[j] * H(j + 1, k);
        H(j, k) = t;
      }
      const double denom = std::hypot(H(k, k), H(k + 1, k));
      cs[k] = H(k, k) / denom;
      sn[k] = H(k + 1, k) / denom;
      H(k, k) = denom;
      g[k + 1] = -sn[k] * g[k];
      g[k] *= cs[k];
      const bool breakdown = H(k + 1, k) == 0.0;
      H(k + 1, k) = 0.0;
      ++k;
      if (std::abs(g[k]) <= tolerance * b_norm || breakdown) break;
      V.push_back(w / w.norm());
    }
    const Eigen::VectorXd y = H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    Eigen::VectorXd z = Eigen::VectorXd::Zero(b.size());
    for (int j = 0; j < k; ++j) z += y[j] * V[j];
    x += M_inv(z);
  }
}

}  // namespace rbcflow
