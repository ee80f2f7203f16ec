#pragma once
// Anderson acceleration of a fixed-point iteration x = F(x) (Anderson, J. ACM 12, 1965; in the
// form of Walker & Ni, SIAM J. Numer. Anal. 49, 2011, with mixing parameter 1): from the
// residuals g_i = F(x_i) - x_i of the last m + 1 iterates, the next iterate is
//   x_{k+1} = F(x_k) - dF gamma,   gamma = argmin |g_k - dG gamma|,
// with the columns of dG and dF the differences of consecutive g_i and F(x_i). For an affine
// F(x) = A x + c it is a Krylov method on (I - A) x = c (with unbounded m, GMRES's iterates,
// Walker & Ni theorem 2.2): where plain iteration contracts by the spectral radius of A a
// sweep, Anderson's iteration converges like GMRES, whatever the spectrum's spread. With m = 0
// it is the plain iteration x_{k+1} = F(x_k).
//
// The iterates are matrices of any shape (the cells' node velocities, P x 3), treated as
// vectors. The least-squares problem is solved from its m x m normal equations by a
// rank-revealing decomposition: m is small, and near convergence the columns of dG become
// nearly dependent; the rank cut then drops the redundant directions.
//
// The next iterate is a combination of the F(x_i), so its image under any linear map L is the
// same combination of the L F(x_i): given those (a solve's by-product: GMRES returns A x for
// its x), next() returns L x_{k+1} without applying L.
//
// Iterates split by rows over ranks (each rank its rows, as GMRES's vectors, parallel/owned_rows.h)
// mix alike on every rank when `sum_parts` sums each rank's partial inner products over them
// (SplitInnerProducts::sum): the least-squares problem is then the whole vectors'.
#include <Eigen/Core>
#include <Eigen/QR>
#include <deque>
#include <functional>
#include <stdexcept>

namespace rbcflow {

class AndersonMixing {
 public:
  explicit AndersonMixing(int depth, std::function<void(Eigen::VectorXd&)> sum_parts = {})
      : depth_(depth), sum_parts_(std::move(sum_parts)) {
    if (depth < 0) throw std::invalid_argument("AndersonMixing: the depth must be >= 0");
  }

  // Given the iterate x and its image F(x), returns the next iterate.
  Eigen::MatrixXd next(const Eigen::MatrixXd& x, const Eigen::MatrixXd& f) { return advance(x, f, nullptr, nullptr); }
  // The same, given also L F(x) for a linear map L, and sets next_image to L x_{k+1} (it may be
  // f_image itself). Give the images at every call or at none (std::logic_error otherwise).
  Eigen::MatrixXd next(const Eigen::MatrixXd& x, const Eigen::MatrixXd& f, const Eigen::MatrixXd& f_image,
                       Eigen::MatrixXd& next_image) {
    return advance(x, f, &f_image, &next_image);
  }

  int depth() const { return depth_; }
  int history() const { return static_cast<int>(dG_.size()); }

 private:
  Eigen::MatrixXd advance(const Eigen::MatrixXd& x, const Eigen::MatrixXd& f, const Eigen::MatrixXd* f_image,
                          Eigen::MatrixXd* next_image) {
    const bool first = previous_g_.size() == 0;
    if (first) with_images_ = f_image != nullptr;
    if ((f_image != nullptr) != with_images_)
      throw std::logic_error("AndersonMixing: the images must be given at every call or at none");
    Eigen::MatrixXd g = f - x;
    if (!first && depth_ > 0) {
      dG_.push_back(g - previous_g_);
      dF_.push_back(f - previous_f_);
      if (with_images_) dL_.push_back(*f_image - previous_image_);
      if (static_cast<int>(dG_.size()) > depth_) {
        dG_.pop_front();
        dF_.pop_front();
        if (with_images_) dL_.pop_front();
      }
    }
    if (with_images_) previous_image_ = *f_image;  // before *next_image is written: they may be one
    const int m = static_cast<int>(dG_.size());
    Eigen::MatrixXd next = f;
    if (with_images_) *next_image = previous_image_;
    if (m > 0) {
      // The normal equations' right-hand side and lower triangle, one vector of inner products.
      Eigen::VectorXd products(m + m * (m + 1) / 2);
      for (int i = 0, k = m; i < m; ++i) {
        products[i] = dot(dG_[i], g);
        for (int j = 0; j <= i; ++j) products[k++] = dot(dG_[i], dG_[j]);
      }
      if (sum_parts_) sum_parts_(products);
      Eigen::MatrixXd gram(m, m);
      const Eigen::VectorXd rhs = products.head(m);
      for (int i = 0, k = m; i < m; ++i)
        for (int j = 0; j <= i; ++j) gram(i, j) = gram(j, i) = products[k++];
      const Eigen::VectorXd gamma = gram.completeOrthogonalDecomposition().solve(rhs);
      for (int i = 0; i < m; ++i) next -= gamma[i] * dF_[i];
      if (with_images_)
        for (int i = 0; i < m; ++i) *next_image -= gamma[i] * dL_[i];
    }
    previous_g_ = std::move(g);
    previous_f_ = f;
    return next;
  }

  static double dot(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) { return a.cwiseProduct(b).sum(); }

  int depth_;
  std::function<void(Eigen::VectorXd&)> sum_parts_;  // empty: the iterates are whole here
  bool with_images_ = false;
  std::deque<Eigen::MatrixXd> dG_, dF_, dL_;  // dL_: differences of the images L F(x_i)
  Eigen::MatrixXd previous_g_, previous_f_, previous_image_;
};

}  // namespace rbcflow
