#pragma once
// Restarted GMRES (Saad & Schultz 1986) for matrix-free operators: A is any callable
// `Eigen::VectorXd(const Eigen::VectorXd&)`. Modified Gram-Schmidt, Givens rotations.
#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace rbcflow {

struct GmresResult {
  int iterations = 0;         // operator applications
  double relative_residual = 0;  // |b - A x| / |b|
  bool converged = false;
};

template <typename Operator>
GmresResult gmres(const Operator& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance,
                  int max_iterations, int restart = 50) {
  GmresResult result;
  const double bnorm = b.norm();
  if (bnorm == 0.0) {
    x.setZero(b.size());
    result.converged = true;
    return result;
  }
  if (x.size() != b.size()) x.setZero(b.size());
  const int m = std::max(1, restart);
  while (result.iterations < max_iterations) {
    Eigen::VectorXd r = b - A(x);
    double beta = r.norm();
    result.relative_residual = beta / bnorm;
    if (result.relative_residual <= tolerance) {
      result.converged = true;
      return result;
    }
    std::vector<Eigen::VectorXd> V{r / beta};
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m);
    Eigen::VectorXd cs = Eigen::VectorXd::Zero(m), sn = Eigen::VectorXd::Zero(m);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(m + 1);
    g[0] = beta;
    int k = 0;
    for (; k < m && result.iterations < max_iterations; ++k) {
      Eigen::VectorXd w = A(V[k]);
      ++result.iterations;
      for (int j = 0; j <= k; ++j) {
        H(j, k) = w.dot(V[j]);
        w -= H(j, k) * V[j];
      }
      H(k + 1, k) = w.norm();
      for (int j = 0; j < k; ++j) {  // apply the previous rotations to the new column
        const double t = cs[j] * H(j, k) + sn[j] * H(j + 1, k);
        H(j + 1, k) = -sn[j] * H(j, k) + cs[j] * H(j + 1, k);
        H(j, k) = t;
      }
      const double denom = std::hypot(H(k, k), H(k + 1, k));
      cs[k] = H(k, k) / denom;
      sn[k] = H(k + 1, k) / denom;
      H(k, k) = denom;
      H(k + 1, k) = 0.0;
      g[k + 1] = -sn[k] * g[k];
      g[k] = cs[k] * g[k];
      result.relative_residual = std::abs(g[k + 1]) / bnorm;
      if (result.relative_residual <= tolerance || H(k, k) == 0.0) {
        ++k;
        break;
      }
      V.push_back(w / (w.norm() > 0 ? w.norm() : 1.0));
      if (w.norm() == 0.0) {
        ++k;
        break;
      }
    }
    // x += V y with H(0:k, 0:k) y = g(0:k).
    const Eigen::VectorXd y = H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    for (int j = 0; j < k; ++j) x += y[j] * V[j];
    if (result.relative_residual <= tolerance) {
      result.relative_residual = (b - A(x)).norm() / bnorm;  // the true residual
      result.converged = result.relative_residual <= 10 * tolerance;
      return result;
    }
  }
  return result;
}

}  // namespace rbcflow
