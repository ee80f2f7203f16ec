#pragma once
// Grids on the unit sphere: colatitudes theta_i times uniform longitudes phi_j = 2 pi j / n_phi.
// A grid point has index p = i * n_phi + j; grid fields are (size() x components) matrices.
#include <Eigen/Core>

namespace rbcflow {

class SphGrid {
 public:
  // The paper's grid (section 3): n_theta Gauss-Legendre colatitudes x n_phi longitudes,
  // n_phi = 2 n_theta by default. It carries a quadrature rule.
  static SphGrid gauss(int n_theta, int n_phi = 0);
  // Colatitudes uniform in [0, pi], both poles included (theta_i = i pi / (n_theta - 1)):
  // the grid of the singular quadrature's splines (section 5.4). No quadrature rule.
  static SphGrid uniform(int n_theta, int n_phi);

  int n_theta() const { return static_cast<int>(theta_.size()); }
  int n_phi() const { return n_phi_; }
  int size() const { return n_theta() * n_phi_; }
  bool is_gauss() const { return weights_.size() > 0; }
  const Eigen::VectorXd& theta() const { return theta_; }
  // Gauss weights for integrals over cos(theta); empty for a uniform grid.
  const Eigen::VectorXd& weights() const { return weights_; }
  double phi(int j) const;
  // Weight of grid point p for integrals over the unit sphere, w_i * 2 pi / n_phi.
  double sphere_weight(int p) const;

 private:
  SphGrid(Eigen::VectorXd theta, Eigen::VectorXd weights, int n_phi);
  Eigen::VectorXd theta_;
  Eigen::VectorXd weights_;
  int n_phi_ = 0;
};

}  // namespace rbcflow
