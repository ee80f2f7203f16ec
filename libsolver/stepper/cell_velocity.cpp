#include "cell_velocity.h"

#include <numbers>
#include <stdexcept>

namespace rbcflow {

VelocitySolve solve_cell_velocity(CellLayers& layers, const Eigen::MatrixXd& traction, double viscosity_ratio,
                                  const Eigen::MatrixXd& background, double tolerance, int max_iterations,
                                  const Eigen::MatrixXd& initial_guess, Eigen::MatrixXd* image) {
  const double lam = viscosity_ratio, pi = std::numbers::pi;
  if (!(lam > 0)) throw std::invalid_argument("solve_cell_velocity: viscosity ratio must be positive");
  const Eigen::MatrixXd rhs = -layers.single_layer(traction) / (4 * pi * (1 + lam)) + (2 / (1 + lam)) * background;
  VelocitySolve s;
  if (lam == 1.0) {
    s.velocity = rhs;
    s.gmres.converged = true;
    if (image) *image = rhs;
    return s;
  }
  const Eigen::Index n = rhs.rows();
  const double c = (1 - lam) / (4 * pi * (1 + lam));
  auto A = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const Eigen::Map<const Eigen::MatrixXd> u(v.data(), n, 3);
    const Eigen::MatrixXd Au = u - c * layers.double_layer(u);
    return Eigen::Map<const Eigen::VectorXd>(Au.data(), Au.size());
  };
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(rhs.data(), rhs.size());
  Eigen::VectorXd x = initial_guess.size() == rhs.size()
                          ? Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(initial_guess.data(), initial_guess.size()))
                          : b;
  Eigen::VectorXd Ax;
  if (image && image->rows() == n && image->cols() == 3 && initial_guess.size() == rhs.size())
    Ax = Eigen::Map<const Eigen::VectorXd>(image->data(), image->size());
  s.gmres = gmres(A, b, x, tolerance, max_iterations, 60, image ? &Ax : nullptr);
  s.velocity = Eigen::Map<const Eigen::MatrixXd>(x.data(), n, 3);
  if (image) *image = Eigen::Map<const Eigen::MatrixXd>(Ax.data(), n, 3);
  return s;
}

}  // namespace rbcflow
