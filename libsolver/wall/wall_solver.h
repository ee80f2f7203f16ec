#pragma once
// The wall solve (12) without cells: find the wall force density f with
//   (1/(8 pi mu)) N_W f = v  at every wall node,
// v the velocity the wall must cancel (<u> minus what the cells induce; <u> alone here), by
// right-preconditioned GMRES. The preconditioner is block-Jacobi with sparse LUs of the local
// near field (NearField::local) on slabs of the wall (wall_preconditioner.h), factorised once;
// build the operator with RealSpace::assembled so that its real-space Ewald part is a sparse
// matrix too. Not converging is an error.
#include <Eigen/Core>
#include <vector>

#include "libsolver/linear/preconditioned_gmres.h"
#include "wall_operator.h"
#include "wall_preconditioner.h"

namespace rbcflow {

struct WallSolveOptions {
  double tolerance = 1e-6;  // relative residual
  int max_iterations = 300;
  int restart = 60;
  // Krylov recycling (preconditioned_gmres.h): the most directions kept from the seed solves
  // (WallSolver::seed) and deflated in every later solve; 0: none. The seeds of the D = 12
  // tube's wall produce 153, 229 and 285 directions at 4,321, 17,545 and 33,803 nodes (the
  // slow modes grow with the tube's length); kept to 150 at 33,803 nodes, a later solve takes
  // 132 iterations instead of 59 (bench/bench_wall.cpp, LongTube).
  int recycle = 300;
  // The nodes of a block of the preconditioner (wall_preconditioner.h), read when the solver
  // is built (WallSolver's constructor): a wall of at most this many nodes is one block, the
  // LU of its whole local near field.
  int preconditioner_block_nodes = 500;
  // The ranks that share the wall operator's assembled rows (wall_operator.h) and the solve's
  // GMRES vectors, each its nodes' segment (WallSolver::solve); default one.
  Communicator ranks{};
};

struct WallSolution {
  PointField force;  // f at the nodes: the force density the fluid exerts on the wall
  GmresReport gmres;
  // Nodes this rank received from the others: the densities its products read, and the nodes of
  // the others' parts of its rows of the products' and the right-hand side's sums.
  long nodes_received = 0;
};

class WallSolver {
 public:
  // `op` must have the wall nodes as its targets; the preconditioner's blocks are of
  // options.preconditioner_block_nodes nodes, shared by op.ranks(). Build `op` with the rows
  // wall_node_segments(nodes, options.preconditioner_block_nodes, ranks) so that the
  // preconditioner needs no other rank.
  explicit WallSolver(WallOperator op, const WallSolveOptions& options = {});

  // Throws std::runtime_error when GMRES stops unconverged. `initial_guess` (one row per node,
  // or empty for zero) is typically the previous step's force. `velocity_part` (one row per
  // node), when given: this rank's part of a further velocity that is the sum of the ranks'
  // parts (the cells' layers at the wall, CellLayersAtPoints), added to `velocity`; each rank
  // then receives only its segment of that sum, never the whole.
  WallSolution solve(const PointField& velocity, double mu, const WallSolveOptions& options = {},
                     const PointField& initial_guess = {}, const PointField* velocity_part = nullptr);

  // Solves for each velocity in turn, keeping the Krylov directions of these solves (up to
  // options.recycle) for all later ones: the same seeds give the same space, so a run and its
  // restart solve alike.
  std::vector<WallSolution> seed(const std::vector<PointField>& velocities, double mu, const WallSolveOptions& options);
  int recycled_directions() const { return recycled_.size(); }
  int preconditioner_blocks() const { return preconditioner_.blocks(); }
  // Whether the operator's segments are the preconditioner's blocks' (wall_node_segments), so
  // that applying it moves nothing between the ranks.
  bool local_preconditioner() const { return local_preconditioner_; }
  // Nodes this rank has received from the others for its solves so far (as WallSolution's).
  long nodes_received() const { return density_reads_.nodes_received() + op_.segments().nodes_received(); }
  // "wall operator: ...", "wall preconditioner (LU)" (this rank's blocks), "wall recycled
  // space" (memory_report.h).
  void report_memory(MemoryReport& report) const;

  WallOperator& op() { return op_; }

 private:
  WallOperator op_;
  WallPreconditioner preconditioner_;
  bool local_preconditioner_;
  // The operator's segments, reading only the nodes a product on this rank reads
  // (WallOperator::density_nodes) when there are several ranks.
  OwnedSegments density_reads_;
  RecycledSpace recycled_;
};

// Eq. (8): <grad p> = -(1/V) int_W f dS.
Eigen::Vector3d mean_pressure_gradient(const WallElements& elements, const PointField& force,
                                       double box_volume);

}  // namespace rbcflow
