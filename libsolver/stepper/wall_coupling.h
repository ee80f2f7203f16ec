#pragma once
// The vessel wall in the staggered scheme of section 2: the wall-wall operator of (12) and
// its preconditioner are built once per run (the wall does not move); each step solves (12),
//   (1/(8 pi mu)) N_W F = <u> - (1/(8 pi mu)) N_D f + (1 - lambda)/(8 pi) K_D U   at the wall
// nodes, for the wall force F, and gives the wall's velocity -(1/(8 pi mu)) N_W F at the cell
// nodes for (10). F is the force density of the fluid on the wall, so <grad p> = -(1/V) int F
// (eq. 8). With a prescribed <grad p>, <u> is found from the wall's response to a unit mean
// velocity along each axis (three solves, once per run): (8) is linear in <u>. The same three
// solves seed the recycled Krylov space of every later wall solve (WallSolveOptions::recycle,
// on by default): they hold the wall's slow global modes, which cut the GMRES iterations of a
// step several-fold in long tubes.
#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>

#include "libsolver/wall/wall_solver.h"

namespace rbcflow {

class WallCoupling {
 public:
  // work_arrays: the pool of its products' grid arrays (work_array_pool.h), shared with the
  // cells' grids by a stepper; a pool of its own when null.
  WallCoupling(std::shared_ptr<const WallElements> wall, const PeriodicBox& box, double ewald_tolerance,
               const WallSolveOptions& options, std::shared_ptr<WorkArrayPool> work_arrays = nullptr);

  const WallElements& elements() const { return *elements_; }
  const PointField& nodes() const { return elements_->wall.surface.points; }
  const PeriodicBox& box() const { return box_; }

  // F for the velocity `v` the wall must cancel at its nodes (mu = 1); `guess` may be empty.
  // A `looser` relative residual than the options' applies to this solve alone. `v_part`:
  // this rank's part of a further velocity summed over the ranks (WallSolver::solve).
  WallSolution solve(const PointField& v, const PointField& guess, double looser = 0,
                     const PointField* v_part = nullptr);
  // <grad p> of (8) for a wall force.
  Eigen::Vector3d pressure_gradient(const PointField& force) const;
  // The mean velocity that gives `target` = <grad p> when the cells alone induce a wall force
  // F_cells (the solution of (12) with <u> = 0); F = F_cells + sum_j <u>_j F_unit_j.
  Eigen::Vector3d mean_velocity_for(const Eigen::Vector3d& target, const PointField& cell_force);
  PointField force_for_mean_velocity(const Eigen::Vector3d& mean_velocity);
  // -(1/(8 pi mu)) N_W F at arbitrary points (the cell nodes), with the near-field correction.
  PointField velocity_at(const PointField& points, const PointField& force) const;
  // The same in two halves, for several forces at the same points (one step's cell nodes):
  // the operator with `points` as targets, then the velocity for a force. chosen_for_points:
  // as WallOperator's chosen_for_targets (one rank's share of the points).
  WallOperator operator_at(const PointField& points, long chosen_for_points = 0) const;
  // One rank's part of the operator at every point of the ranks (WallOperator's TargetRows
  // constructor): the near field and real space at its `rows`, the smooth part on its slab;
  // `all_points` as that constructor's all_targets.
  WallOperator operator_at(const PointField& points, TargetRows rows, const Communicator& ranks,
                           long all_points = 0) const;
  // The grid of that operator at `targets` points (WallOperator::grid_at_rows).
  std::shared_ptr<const SpmeGrid> grid_at(long targets, const Communicator& ranks) const;
  static PointField velocity_at(WallOperator& at_points, const PointField& force);
  void report_memory(MemoryReport& report) const {
    solver_.report_memory(report);
    report.add("wall SPME grids", grid_cache_->memory_bytes());
  }

 private:
  const std::array<PointField, 3>& unit_forces();

  std::shared_ptr<const WallElements> elements_;
  PeriodicBox box_;
  double ewald_tolerance_;
  WallSolveOptions options_;
  // The SPME grids of the wall's operators (its own and operator_at's), kept for the run.
  std::unique_ptr<SpmeGridCache> grid_cache_;
  WallSolver solver_;
  std::optional<std::array<PointField, 3>> unit_forces_;
};

}  // namespace rbcflow
