#pragma once
// Restarted GMRES (Saad & Schultz 1986) with right preconditioning: solves A M^{-1} y = b,
// x = M^{-1} y, so the residual it monitors is the true one, |b - A x| / |b|. A and M^{-1}
// are callables Eigen::VectorXd(const Eigen::VectorXd&). Modified Gram-Schmidt, Givens
// rotations; the initial guess is x. The one GMRES of rbcflow: the wall solve (12) uses it
// preconditioned and recycled, the cells' solve (10) plain (gmres below).
//
// Krylov recycling (GCRO, de Sturler 1999; Parks et al., SIAM J. Sci. Comput. 28, 2006) for a
// sequence of systems with the same A and M: a RecycledSpace holds U and C with
// A M^{-1} U = C and C^T C = I. The solve first removes the part of the residual in range(C)
// exactly (x += M^{-1} U C^T r) and then runs GMRES on (I - C C^T) A M^{-1}, whose spectrum
// lacks the directions in C: the slow, global modes that every solve would otherwise rebuild.
// A solve may also grow the space with its own Arnoldi vectors, up to a capacity.
#include <Eigen/Core>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace rbcflow {

// The inner products of GMRES's vectors, whole on this process. A solve whose vectors are split
// over ranks passes its own (SplitInnerProducts, parallel/owned_rows.h): the same operations,
// each summing the ranks' parts, and all() true only where it is on every rank (a decision the
// ranks must take alike: a rank holding no rows cannot tell from its sizes alone).
struct LocalInnerProducts {
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const { return a.dot(b); }
  double norm(const Eigen::VectorXd& a) const { return a.norm(); }
  void sum(Eigen::VectorXd&) const {}  // of partial inner products (C^T r with C split by rows)
  bool all(bool here) const { return here; }
};

struct GmresReport {
  int iterations = 0;  // operator applications inside the Krylov cycles
  double relative_residual = 0.0;
  bool converged = false;
};

struct RecycledSpace {
  Eigen::MatrixXd U, C;  // n x k: A M^{-1} U = C, C orthonormal
  int size() const { return static_cast<int>(C.cols()); }
  int capacity = 0;      // grow() adds columns up to this many
  bool growing = false;  // whether a solve adds its Arnoldi vectors

  // Appends the directions of one GMRES cycle: with W = V_k - U B (its search directions,
  // deflated) and the Arnoldi relation A M^{-1} W = V_{k+1} Hbar, Hbar = Q R gives
  // A M^{-1} (W R^{-1}) = V_{k+1} Q, orthonormal and orthogonal to C.
  void grow(const std::vector<Eigen::VectorXd>& V, const Eigen::MatrixXd& Hbar, const Eigen::MatrixXd& B, int k) {
    k = std::min(k, capacity - size());
    if (k <= 0 || static_cast<int>(V.size()) < k + 1) return;
    const Eigen::HouseholderQR<Eigen::MatrixXd> qr(Hbar.topLeftCorner(k + 1, k));
    const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(k + 1, k);
    const Eigen::MatrixXd R = qr.matrixQR().topLeftCorner(k, k).triangularView<Eigen::Upper>();
    if ((R.diagonal().array().abs() < 1e-12 * R.diagonal().cwiseAbs().maxCoeff()).any()) return;
    const Eigen::Index n = V[0].size();
    Eigen::MatrixXd W(n, k), Vk1(n, k + 1);
    for (int j = 0; j <= k; ++j) {
      Vk1.col(j) = V[j];
      if (j < k) W.col(j) = V[j];
    }
    if (size() > 0) W -= U * B.leftCols(k);
    const Eigen::MatrixXd Unew = R.transpose().triangularView<Eigen::Lower>().solve(W.transpose()).transpose();
    const Eigen::MatrixXd Cnew = Vk1 * Q;
    const int old = size();
    U.conservativeResize(n, old + k);
    C.conservativeResize(n, old + k);
    U.rightCols(k) = Unew;
    C.rightCols(k) = Cnew;
  }
};

//
// `image` (optional): on entry, when it has b's size, A x for the initial x, which the first
// residual then takes instead of a product; on return, A x for the returned x, from the
// Arnoldi relation (b less the residual the cycle leaves) where the solve ends in a cycle:
// what a caller whose next guess is a combination of solutions needs, at no product.
// `products`: the inner products (above); the vectors may be this rank's rows only.
template <typename Operator, typename Preconditioner, typename InnerProducts = LocalInnerProducts>
GmresReport preconditioned_gmres(Operator&& A, Preconditioner&& M_inv, const Eigen::VectorXd& b,
                                 Eigen::VectorXd& x, double tolerance, int max_iterations,
                                 int restart = 60, RecycledSpace* recycled = nullptr,
                                 Eigen::VectorXd* image = nullptr, const InnerProducts& products = {}) {
  GmresReport report;
  const double b_norm = products.norm(b);
  if (x.size() != b.size()) x = Eigen::VectorXd::Zero(b.size());
  if (b_norm == 0.0) {
    x.setZero();
    if (image) *image = Eigen::VectorXd::Zero(b.size());
    report.converged = true;
    return report;
  }
  bool image_known = products.all(image && image->size() == b.size());
  while (true) {
    Eigen::VectorXd r = b - (image_known ? *image : Eigen::VectorXd(A(x)));
    image_known = false;  // a restart recomputes the residual
    report.relative_residual = products.norm(r) / b_norm;
    if (report.relative_residual <= tolerance || report.iterations >= max_iterations) {
      report.converged = report.relative_residual <= tolerance;
      if (image) *image = b - r;
      return report;
    }
    const int p = recycled ? recycled->size() : 0;
    if (p > 0) {  // the part of r in range(C), removed exactly
      Eigen::VectorXd c = recycled->C.transpose() * r;
      products.sum(c);
      x += M_inv(Eigen::VectorXd(recycled->U * c));
      r -= recycled->C * c;
    }
    const double beta = products.norm(r);
    const int m = std::max(1, restart);
    std::vector<Eigen::VectorXd> V{r / beta};
    Eigen::MatrixXd H = Eigen::MatrixXd::Zero(m + 1, m), Hbar = H, B = Eigen::MatrixXd::Zero(p, m);
    Eigen::VectorXd cs(m), sn(m), g = Eigen::VectorXd::Zero(m + 1);
    g[0] = beta;
    int k = 0;
    bool breakdown = false;
    while (k < m && report.iterations < max_iterations) {
      Eigen::VectorXd w = A(M_inv(V[k]));
      ++report.iterations;
      for (int pass = 0; pass < 2 && p > 0; ++pass) {  // twice: C is large, keep w orthogonal to it
        Eigen::VectorXd c = recycled->C.transpose() * w;
        products.sum(c);
        B.col(k) += c;
        w -= recycled->C * c;
      }
      for (int j = 0; j <= k; ++j) {
        H(j, k) = products.dot(w, V[j]);
        w -= H(j, k) * V[j];
      }
      H(k + 1, k) = products.norm(w);
      Hbar.col(k) = H.col(k);
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
      breakdown = Hbar(k + 1, k) == 0.0;
      H(k + 1, k) = 0.0;
      if (!breakdown) V.push_back(w / Hbar(k + 1, k));
      ++k;
      if (std::abs(g[k]) <= tolerance * b_norm || breakdown) break;
    }
    const Eigen::VectorXd y = H.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    Eigen::VectorXd z = Eigen::VectorXd::Zero(b.size());
    for (int j = 0; j < k; ++j) z += y[j] * V[j];
    if (p > 0) z -= recycled->U * (B.leftCols(k) * y);
    x += M_inv(z);
    if (recycled && recycled->growing && !breakdown) recycled->grow(V, Hbar, B, k);
    // |g_k| is the norm of b - A x for the new x (the Arnoldi relation; with a recycled space,
    // A M^{-1} (V_k - U B) = V_{k+1} Hbar), so a converged cycle ends without the product that
    // would recompute it: one operator application fewer per solve.
    if (std::abs(g[k]) <= tolerance * b_norm) {
      report.relative_residual = std::abs(g[k]) / b_norm;
      report.converged = true;
      if (image) {  // A M^{-1} z = V_{k+1} Hbar y: the residual left is r - V_{k+1} Hbar y
        const Eigen::VectorXd h = Hbar.topLeftCorner(k + 1, k) * y;
        for (int j = 0; j <= k && j < static_cast<int>(V.size()); ++j) r -= h[j] * V[j];
        *image = b - r;
      }
      return report;
    }
  }
}

// Unpreconditioned (M = I): for operators as well conditioned as the cells' A11 of (10).
template <typename Operator, typename InnerProducts = LocalInnerProducts>
GmresReport gmres(Operator&& A, const Eigen::VectorXd& b, Eigen::VectorXd& x, double tolerance, int max_iterations,
                  int restart = 60, Eigen::VectorXd* image = nullptr, const InnerProducts& products = {}) {
  return preconditioned_gmres(std::forward<Operator>(A), [](const Eigen::VectorXd& v) { return v; }, b, x, tolerance,
                              max_iterations, restart, nullptr, image, products);
}

}  // namespace rbcflow
