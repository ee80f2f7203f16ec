#include "wall_solver.h"

#include <numbers>
#include <stdexcept>
#include <string>

#include "libsolver/common/memory_report.h"

namespace rbcflow {

namespace {

const WallOperator& wall_targets(const WallOperator& op, const WallSolveOptions& options) {
  if (op.num_targets() != op.elements().num_nodes())
    throw std::invalid_argument("wall solver: the operator's targets must be the wall nodes");
  // The preconditioner's blocks read the local near field at their nodes' rows.
  if (op.near_at_rows_only() &&
      !(op.segments() == wall_node_segments(op.targets(), options.preconditioner_block_nodes, op.ranks())))
    throw std::invalid_argument(
        "wall solver: the operator holds the near field at its rows only, and they are not the preconditioner's "
        "slabs: build it with wall_node_segments of the same block size");
  return op;
}

}  // namespace

WallSolver::WallSolver(WallOperator op, const WallSolveOptions& options)
    : op_(std::move(op)),
      preconditioner_(wall_targets(op_, options).near().local, op_.targets(), options.preconditioner_block_nodes, op_.ranks()),
      local_preconditioner_(preconditioner_.matches(op_.segments())),
      density_reads_(op_.segments()) {
  op_.release_local_near_field();  // the factorisations keep their own copies
  if (op_.ranks().size() > 1) density_reads_.read_only(op_.density_nodes());
}

WallSolution WallSolver::solve(const PointField& velocity, double mu, const WallSolveOptions& options,
                               const PointField& initial_guess, const PointField* velocity_part) {
  // GMRES's vectors (the Krylov basis, the recycled space) are this rank's segment of the nodes
  // (parallel/owned_rows.h), those of its rows of the operator; a product first brings from
  // their owners the densities of the nodes it reads (its rows' blocks, the nodes its slab of the
  // grid spreads). The preconditioner reads and writes only the segment when the segments are
  // its blocks' (wall_node_segments), else it gathers the whole.
  const OwnedSegments& nodes = op_.segments();
  if (velocity_part && (velocity_part->rows() != velocity.rows() || velocity_part->cols() != velocity.cols()))
    throw std::invalid_argument("WallSolver::solve: the velocity's part is not one row a node");
  const long received = nodes_received();
  const double scale = 8.0 * std::numbers::pi * mu;
  Eigen::VectorXd b;
  if (!velocity_part) {
    b = nodes.mine(scale * to_vector(velocity));
  } else if (op_.ranks().size() == 1) {
    b = nodes.mine(scale * to_vector(velocity + *velocity_part));
  } else {
    b = nodes.mine(scale * to_vector(velocity)) + nodes.sum_mine(scale * to_vector(*velocity_part));
  }
  Eigen::VectorXd x = initial_guess.rows() == velocity.rows() ? nodes.mine(to_vector(initial_guess))
                                                              : Eigen::VectorXd::Zero(b.size());
  auto A = [&](const Eigen::VectorXd& f) { return op_.apply_mine(to_field(density_reads_.gather_read(f))); };
  auto M_inv = [&](const Eigen::VectorXd& r) {
    return local_preconditioner_ ? preconditioner_.solve_segment(r, nodes)
                                 : preconditioner_.solve_mine(nodes.gather(r), nodes);
  };
  WallSolution s;
  s.gmres = preconditioned_gmres(A, M_inv, b, x, options.tolerance, options.max_iterations, options.restart, &recycled_,
                                 nullptr, SplitInnerProducts{op_.ranks()});
  if (!s.gmres.converged)
    throw std::runtime_error("wall solve did not converge: relative residual " +
                             std::to_string(s.gmres.relative_residual) + " after " +
                             std::to_string(s.gmres.iterations) + " GMRES iterations");
  s.nodes_received = nodes_received() - received;
  x = nodes.gather(x);
  s.force = to_field(x);
  return s;
}

std::vector<WallSolution> WallSolver::seed(const std::vector<PointField>& velocities, double mu,
                                          const WallSolveOptions& options) {
  recycled_.capacity = options.recycle;
  recycled_.growing = options.recycle > 0;
  std::vector<WallSolution> out;
  try {
    for (const PointField& v : velocities) out.push_back(solve(v, mu, options));
  } catch (...) {
    recycled_.growing = false;
    throw;
  }
  recycled_.growing = false;
  return out;
}

Eigen::Vector3d mean_pressure_gradient(const WallElements& elements, const PointField& force,
                                       double box_volume) {
  return -elements.total(force) / box_volume;
}

void WallSolver::report_memory(MemoryReport& report) const {
  op_.report_memory(report, "wall operator");
  report.add("wall preconditioner (LU)", preconditioner_.bytes());
  report.add("wall recycled space", matrix_bytes(recycled_.U) + matrix_bytes(recycled_.C));
}

}  // namespace rbcflow
