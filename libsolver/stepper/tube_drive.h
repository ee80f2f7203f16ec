#pragma once
// The flow in a vessel that is a straight circular tube about a known section: its mean
// velocity U (the tube velocity) measured, and held at a target by choosing <u> every step.
// In the periodic formulation (6)-(8) the flow is set by the box mean <u>, but part of the box's
// flux passes outside the vessel (eq. 45: 70% for a D = 3.5 tube in a 5 x 5 box), and a
// constriction's neck sends more of it round.
//
// The box's flux A_box <u> (any cross-section: the flow is solenoidal, cells included) is the
// tube's, pi a^2 U, plus the flux outside the vessel. No cell is outside, so that flux is Stokes
// flow driven by the mean pressure gradient alone: Q_out = -k dp/dx_axis, with one constant k.
// A cell-free wall solve per unit <u> gives k: there the flow about the section is Poiseuille,
// so U is half the velocity on the axis (`ratio` = U / <u> without cells), and k follows from
// A_box = pi a^2 ratio + k (-dp/dx per unit <u>). With cells, U = (A_box <u> + k dp/dx) / (pi a^2).
// Stokes flow is linear in <u>: for the part dp0 of the gradient that the cells and walls give at
// <u> = 0, U = ratio <u> + k dp0 / (pi a^2), so one <u> holds U exactly within each step.
#include <Eigen/Core>

#include "wall_coupling.h"

namespace rbcflow {

// Where the vessel is a straight tube of `radius` about `axis_point` (on its axis, which is box
// axis `axis`), for a few radii along it.
struct TubeSection {
  Eigen::Vector3d axis_point = Eigen::Vector3d::Zero();
  int axis = 2;
  double radius = 0.0;
  // Whether the vessel is this tube all along the period (a tube, a constriction) and holds
  // every cell: then the cells' flux over the period gives H_D and their outer edge the
  // cell-free layer. A bifurcation's parent is a tube for part of the period only; the
  // flux outside the vessel is still known (the parent is the one vessel through the box face).
  bool whole_period = true;
};

// Tube mean velocity at `axis_point` per unit <u> along `axis` (0, 1, 2), without cells.
double tube_velocity_per_mean_velocity(WallCoupling& wall, const Eigen::Vector3d& axis_point, int axis);

class TubeFlowMeter {
 public:
  // Throws std::invalid_argument for an axis outside 0..2 or a radius that is not positive.
  TubeFlowMeter(WallCoupling& wall, const TubeSection& section);

  const TubeSection& section() const { return section_; }
  // U / <u> without cells.
  double ratio() const { return ratio_; }
  // U for the box mean velocity and the mean pressure gradient along the axis.
  double tube_velocity(double mean_velocity, double pressure_gradient) const;
  // The <u> along the axis that gives the tube velocity U, where dp/dx along the axis is
  // `gradient_at_rest` at <u> = 0 (the cells' and walls' own part).
  double mean_velocity_for(double tube_velocity, double gradient_at_rest) const;

 private:
  TubeSection section_;
  double ratio_ = 0.0;
  double box_section_ = 0.0, tube_section_ = 0.0;
  double outside_per_gradient_ = 0.0;  // k: Q_out = -k dp/dx
};

}  // namespace rbcflow
