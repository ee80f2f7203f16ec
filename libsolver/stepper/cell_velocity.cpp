#include "cell_velocity.h"

#include <numbers>
#include <stdexcept>

#include "libsolver/parallel/owned_rows.h"

namespace rbcflow {

VelocitySolve solve_cell_velocity(CellLayers& layers, const Eigen::MatrixXd& traction, double viscosity_ratio,
                                  const Eigen::MatrixXd& background, double tolerance, int max_iterations,
                                  const Eigen::MatrixXd& initial_guess, Eigen::MatrixXd* image,
                                  const Eigen::MatrixXd* background_part) {
  const double lam = viscosity_ratio, pi = std::numbers::pi;
  if (!(lam > 0)) throw std::invalid_argument("solve_cell_velocity: viscosity ratio must be positive");
  const Eigen::Index total = static_cast<Eigen::Index>(layers.num_cells()) * layers.nodes_per_cell();
  const Eigen::Index held = layers.nodes().size(), owned = static_cast<Eigen::Index>(layers.owned().size()) * layers.nodes_per_cell();
  if ((background.rows() != total && background.rows() != owned) || background.cols() != 3 ||
      (background_part && (background_part->rows() != held || background_part->cols() != 3)))
    throw std::invalid_argument("solve_cell_velocity: background is not one row a node");
  if (traction.rows() != held || traction.cols() != 3)
    throw std::invalid_argument("solve_cell_velocity: traction is not one row a held node");
  // GMRES's vectors are this rank's cells' rows (parallel/owned_rows.h): a product brings the
  // rows of the density this rank reads (its cells' and those its slab of the grid spreads)
  // from their owners into the rows the layers hold, and each rank receives only its rows of
  // the sum of the ranks' parts, from the ranks whose parts reach them. The parts' uniform term
  // is summed apart. The right-hand side arrives the same way: each rank's part of N f and of
  // the background.
  // The products in the layers' held layout: no vector of every cell's rows on several ranks.
  const Communicator& ranks = layers.domain().ranks;
  OwnedRows rows(layers.owned_first(), layers.nodes_per_cell(), ranks);
  if (ranks.size() > 1) rows.hold(layers.held_cells());
  const Eigen::Index n = rows.rows();
  const Eigen::MatrixXd& u_b = background.rows() == n ? background : rows.mine(background);  // this rank's rows
  Eigen::MatrixXd b_mine;
  if (ranks.size() == 1) {
    const Eigen::MatrixXd u_sum = background_part ? Eigen::MatrixXd(u_b + *background_part) : u_b;
    b_mine = -layers.held_single_layer_part(traction) / (4 * pi * (1 + lam)) + (2 / (1 + lam)) * u_sum;
  } else {
    Eigen::MatrixXd part = -layers.held_single_layer_part(traction) / (4 * pi * (1 + lam));
    if (background_part) part += (2 / (1 + lam)) * *background_part;
    b_mine = rows.sum_mine_held(part) + (2 / (1 + lam)) * u_b;
  }
  VelocitySolve s;
  if (lam == 1.0) {
    s.velocity = b_mine;
    s.gmres.converged = true;
    s.rows_received = rows.rows_received();
    if (image) *image = s.velocity;
    return s;
  }
  if (ranks.size() > 1) rows.read_only(layers.density_rows());
  const double c = (1 - lam) / (4 * pi * (1 + lam));
  auto A = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
    const Eigen::Map<const Eigen::MatrixXd> u(v.data(), n, 3);
    if (ranks.size() == 1) {
      const Eigen::MatrixXd Au = u - c * layers.double_layer_part(u);
      return Eigen::Map<const Eigen::VectorXd>(Au.data(), Au.size());
    }
    Eigen::RowVector3d uniform;
    Eigen::MatrixXd Ku = rows.sum_mine_held(layers.held_double_layer_part(rows.gather_read_held(u), &uniform));
    ranks.sum(uniform);
    Ku.rowwise() += uniform;
    const Eigen::MatrixXd Au = u - c * Ku;
    return Eigen::Map<const Eigen::VectorXd>(Au.data(), Au.size());
  };
  auto mine = [&](const Eigen::MatrixXd& all) {  // every node's rows or this rank's already
    const Eigen::MatrixXd m = all.rows() == total ? rows.mine(all) : all;
    return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(m.data(), m.size()));
  };
  auto as_rows = [&](const Eigen::VectorXd& v) { return Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(v.data(), n, 3)); };
  const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(b_mine.data(), b_mine.size());
  const bool guessed = (initial_guess.rows() == total || initial_guess.rows() == n) && initial_guess.cols() == 3;
  Eigen::VectorXd x = guessed ? mine(initial_guess) : b;
  Eigen::VectorXd Ax;
  if (image && guessed && image->rows() == initial_guess.rows() && image->cols() == 3) Ax = mine(*image);
  s.gmres = gmres(A, b, x, tolerance, max_iterations, 60, image ? &Ax : nullptr, SplitInnerProducts{layers.domain().ranks});
  s.rows_received = rows.rows_received();
  s.velocity = as_rows(x);
  if (image) *image = as_rows(Ax);
  return s;
}

}  // namespace rbcflow
