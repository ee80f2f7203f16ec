#include "tube_drive.h"

#include <stdexcept>

namespace rbcflow {

double tube_velocity_per_mean_velocity(WallCoupling& wall, const Eigen::Vector3d& axis_point, int axis) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("tube velocity: the axis must be 0, 1 or 2");
  Eigen::Vector3d unit = Eigen::Vector3d::Zero();
  unit[axis] = 1.0;
  const PointField force = wall.force_for_mean_velocity(unit);  // the recycling seeds: no new solve
  const double on_axis = 1.0 + wall.velocity_at(PointField(axis_point.transpose()), force)(0, axis);
  return 0.5 * on_axis;
}

}  // namespace rbcflow
