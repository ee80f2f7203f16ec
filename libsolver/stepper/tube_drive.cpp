#include "tube_drive.h"

#include <numbers>
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

TubeFlowMeter::TubeFlowMeter(WallCoupling& wall, const TubeSection& section) : section_(section) {
  if (!(section.radius > 0)) throw std::invalid_argument("tube velocity: the tube radius must be positive");
  ratio_ = tube_velocity_per_mean_velocity(wall, section.axis_point, section.axis);
  const int a = section.axis;
  const Eigen::Vector3d sides = wall.box().lengths();
  box_section_ = sides[(a + 1) % 3] * sides[(a + 2) % 3];
  tube_section_ = std::numbers::pi * section.radius * section.radius;
  Eigen::Vector3d unit = Eigen::Vector3d::Zero();
  unit[a] = 1.0;
  const double gradient_per_unit = wall.pressure_gradient(wall.force_for_mean_velocity(unit))[a];  // < 0
  outside_per_gradient_ = (box_section_ - tube_section_ * ratio_) / -gradient_per_unit;
}

double TubeFlowMeter::tube_velocity(double mean_velocity, double pressure_gradient) const {
  return (box_section_ * mean_velocity + outside_per_gradient_ * pressure_gradient) / tube_section_;
}

double TubeFlowMeter::mean_velocity_for(double tube_velocity, double gradient_at_rest) const {
  return (tube_velocity - outside_per_gradient_ * gradient_at_rest / tube_section_) / ratio_;
}

}  // namespace rbcflow
