#pragma once
// Real spherical-harmonic coefficients of eq. (13): degrees n < N (N^2 modes) for each of
// `components` fields (3 for a surface x(theta, phi)).
//
// Layout (rows of values()): block m = 0 holds a_{n0}, n = 0..N-1; each block m >= 1 holds
// a_{nm} for n = m..N-1 followed by b_{nm} for n = m..N-1. Blocks are ordered by m.
#include <Eigen/Core>

namespace rbcflow {

class SHCoeffs {
 public:
  SHCoeffs() = default;
  SHCoeffs(int order, int components);  // zero coefficients

  int order() const { return order_; }
  int components() const { return static_cast<int>(values_.cols()); }
  Eigen::MatrixXd& values() { return values_; }
  const Eigen::MatrixXd& values() const { return values_; }

  static int cos_offset(int order, int m) { return m == 0 ? 0 : (2 * m - 1) * order - m * (m - 1); }
  static int sin_offset(int order, int m) { return cos_offset(order, m) + (order - m); }
  int cos_index(int n, int m) const { return cos_offset(order_, m) + (n - m); }
  int sin_index(int n, int m) const { return sin_offset(order_, m) + (n - m); }

  double& a(int n, int m, int c = 0) { return values_(cos_index(n, m), c); }
  double a(int n, int m, int c = 0) const { return values_(cos_index(n, m), c); }
  double& b(int n, int m, int c = 0) { return values_(sin_index(n, m), c); }
  double b(int n, int m, int c = 0) const { return values_(sin_index(n, m), c); }

  // Zero-padded (new_order > N) or truncated (new_order < N) copy: the de-aliasing resampling
  // of section 10 in coefficient space.
  SHCoeffs resampled(int new_order) const;

  // Energy spectrum of eq. (44): E_n = sum_m sum_components (a_nm^2 + b_nm^2), n = 0..N-1.
  Eigen::VectorXd spectrum() const;

 private:
  int order_ = 0;
  Eigen::MatrixXd values_;
};

}  // namespace rbcflow
