#include "geometry/sph/sph_grid.h"

#include <numbers>
#include <stdexcept>
#include <string>

#include "geometry/sph/gauss_legendre.h"

namespace rbcflow {

SphGrid::SphGrid(Eigen::VectorXd theta, Eigen::VectorXd weights, int n_phi)
    : theta_(std::move(theta)), weights_(std::move(weights)), n_phi_(n_phi) {}

SphGrid SphGrid::gauss(int n_theta, int n_phi) {
  if (n_theta < 1) throw std::invalid_argument("SphGrid::gauss: n_theta must be >= 1");
  if (n_phi == 0) n_phi = 2 * n_theta;
  if (n_phi < 1) throw std::invalid_argument("SphGrid::gauss: n_phi must be >= 1");
  GaussLegendreRule rule = gauss_legendre(n_theta);
  return SphGrid(std::move(rule.theta), std::move(rule.weights), n_phi);
}

SphGrid SphGrid::uniform(int n_theta, int n_phi) {
  if (n_theta < 2 || n_phi < 1) {
    throw std::invalid_argument("SphGrid::uniform: need n_theta >= 2 and n_phi >= 1, got " +
                                std::to_string(n_theta) + " x " + std::to_string(n_phi));
  }
  Eigen::VectorXd theta(n_theta);
  for (int i = 0; i < n_theta; ++i) theta[i] = std::numbers::pi * i / (n_theta - 1);
  return SphGrid(std::move(theta), Eigen::VectorXd(), n_phi);
}

double SphGrid::phi(int j) const { return 2.0 * std::numbers::pi * j / n_phi_; }

double SphGrid::sphere_weight(int p) const {
  return weights_[p / n_phi_] * 2.0 * std::numbers::pi / n_phi_;
}

}  // namespace rbcflow
