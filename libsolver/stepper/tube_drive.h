#pragma once
// Driving a vessel at a prescribed tube velocity. In the periodic formulation (6)-(8) the
// flow is set by the box mean <u>, but part of that flux passes outside the vessel (eq. 45:
// 70% for a D = 3.5 tube in a 5 x 5 box), and a constriction's neck sends more of it round.
// Where the vessel is a straight circular tube for a few radii about `axis_point` (on its
// axis, which is box axis `axis`), the flow there is Poiseuille, so the tube's mean velocity
// is half the velocity on the axis. Stokes flow is linear in <u>, so one cell-free wall
// solve per unit <u> gives the ratio, and <u> = U / ratio drives the tube at mean velocity U
// (cell-free; cells then slow the flow as they raise the effective viscosity).
#include <Eigen/Core>

#include "wall_coupling.h"

namespace rbcflow {

// Drive the flow at tube mean velocity `velocity` along box axis `axis`, measured where the
// vessel is a straight tube about `axis_point` (on its axis).
struct TubeDrive {
  double velocity = 0;
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  int axis = 2;
};

// Tube mean velocity at `axis_point` per unit <u> along `axis` (0, 1, 2), without cells.
double tube_velocity_per_mean_velocity(WallCoupling& wall, const Eigen::Vector3d& axis_point, int axis);

}  // namespace rbcflow
