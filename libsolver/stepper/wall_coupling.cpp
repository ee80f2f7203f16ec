#include "wall_coupling.h"

#include <Eigen/LU>
#include <numbers>

namespace rbcflow {

WallCoupling::WallCoupling(std::shared_ptr<const WallElements> wall, const PeriodicBox& box, double ewald_tolerance,
                           const WallSolveOptions& options, std::shared_ptr<WorkArrayPool> work_arrays)
    : elements_(std::move(wall)),
      box_(box),
      ewald_tolerance_(ewald_tolerance),
      options_(options),
      grid_cache_(work_arrays ? std::make_unique<SpmeGridCache>(std::move(work_arrays)) : std::make_unique<SpmeGridCache>()),
      solver_(WallOperator(elements_, elements_->wall.surface.points, box, ewald_tolerance, grid_cache_.get(),
                           WallOperator::RealSpace::assembled, 0, options.ranks, kAssembledRealSpace,
                           wall_node_segments(elements_->wall.surface.points, options.preconditioner_block_nodes,
                                              options.ranks)),
              options) {
  if (options_.recycle > 0) unit_forces();  // the seeds of the recycled Krylov space
}

WallSolution WallCoupling::solve(const PointField& v, const PointField& guess, double looser, const PointField* v_part) {
  if (looser <= options_.tolerance) return solver_.solve(v, 1.0, options_, guess, v_part);
  WallSolveOptions options = options_;
  options.tolerance = looser;
  return solver_.solve(v, 1.0, options, guess, v_part);
}

Eigen::Vector3d WallCoupling::pressure_gradient(const PointField& force) const {
  return mean_pressure_gradient(*elements_, force, box_.volume());
}

const std::array<PointField, 3>& WallCoupling::unit_forces() {
  if (!unit_forces_) {
    std::vector<PointField> unit_velocities;
    for (int j = 0; j < 3; ++j) {
      Eigen::RowVector3d e = Eigen::RowVector3d::Zero();
      e[j] = 1.0;
      unit_velocities.push_back(e.replicate(elements_->num_nodes(), 1));
    }
    const std::vector<WallSolution> s = solver_.seed(unit_velocities, 1.0, options_);
    unit_forces_ = std::array<PointField, 3>{s[0].force, s[1].force, s[2].force};
  }
  return *unit_forces_;
}

Eigen::Vector3d WallCoupling::mean_velocity_for(const Eigen::Vector3d& target, const PointField& cell_force) {
  Eigen::Matrix3d R;  // <grad p> per unit <u>_j
  for (int j = 0; j < 3; ++j) R.col(j) = pressure_gradient(unit_forces()[j]);
  const Eigen::Vector3d rest = cell_force.rows() ? pressure_gradient(cell_force) : Eigen::Vector3d::Zero();
  return R.fullPivLu().solve(target - rest);
}

PointField WallCoupling::force_for_mean_velocity(const Eigen::Vector3d& mean_velocity) {
  PointField f = PointField::Zero(elements_->num_nodes(), 3);
  for (int j = 0; j < 3; ++j) f += mean_velocity[j] * unit_forces()[j];
  return f;
}

PointField WallCoupling::velocity_at(const PointField& points, const PointField& force) const {
  WallOperator op = operator_at(points);
  return velocity_at(op, force);
}

WallOperator WallCoupling::operator_at(const PointField& points, long chosen_for_points) const {
  return WallOperator(elements_, points, box_, ewald_tolerance_, grid_cache_.get(), WallOperator::RealSpace::per_product,
                      chosen_for_points);
}

WallOperator WallCoupling::operator_at(const PointField& points, TargetRows rows, const Communicator& ranks,
                                       long all_points) const {
  return WallOperator(elements_, points, rows, box_, ewald_tolerance_, grid_cache_.get(), ranks, all_points);
}

std::shared_ptr<const SpmeGrid> WallCoupling::grid_at(long targets, const Communicator& ranks) const {
  return WallOperator::grid_at_rows(grid_cache_.get(), ewald_tolerance_, box_, elements_->points.rows(), targets, ranks);
}

PointField WallCoupling::velocity_at(WallOperator& at_points, const PointField& force) {
  return (-1.0 / (8.0 * std::numbers::pi)) * at_points.apply(force);
}

}  // namespace rbcflow
