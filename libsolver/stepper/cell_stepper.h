#pragma once
// Time advancement of cells without walls (steps (i)-(ii) of section 2, eq. 10-11): membrane
// traction on the de-aliasing grid, the velocity of eq. (6), then X += dt U (forward Euler,
// eq. 11) or second-order Adams-Bashforth, and optionally the volume constraint of section
// 10.2 (a normal correction of each cell to its initial volume).
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

#include "libsolver/membrane/membrane_force.h"
#include "libsolver/operators/cell_layers.h"
#include "libsolver/stepper/cell_velocity.h"

namespace rbcflow {

enum class TimeScheme { euler, ab2 };

struct CellStepperOptions {
  double dt = 1e-3;
  TimeScheme scheme = TimeScheme::euler;
  double viscosity_ratio = 1.0;
  LayerDomain domain;                     // periodic box (mean velocity below) or free space
  Eigen::Vector3d mean_velocity = Eigen::Vector3d::Zero();        // <u> of eq. (6), periodic
  std::function<Eigen::Vector3d(const Eigen::Vector3d&)> background;  // free space: u_inf(x)
  double gmres_tolerance = 1e-6;
  int gmres_max_iterations = 100;
  bool volume_constraint = false;
  QuadratureOptions quadrature;
};

struct Cell {
  SHSurface shape;                       // current surface, order N
  std::shared_ptr<const Membrane> membrane;
  Eigen::Vector3d body_force = Eigen::Vector3d::Zero();  // net external force on the cell
};

struct StepReport {
  int gmres_iterations = 0;
  double gmres_residual = 0.0;
  double max_volume_error = 0.0;  // relative to each cell's initial volume
  double max_area_error = 0.0;
};

class CellStepper {
 public:
  CellStepper(std::vector<Cell> cells, std::shared_ptr<const CellGrids> grids, CellStepperOptions options);

  StepReport step();
  double time() const { return time_; }
  long steps() const { return steps_; }
  const std::vector<Cell>& cells() const { return cells_; }
  // Surface velocity of the last step, stacked over cells (nodes x 3).
  const Eigen::MatrixXd& velocity() const { return velocity_; }

 private:
  void enforce_volume(int c);

  std::vector<Cell> cells_;
  std::shared_ptr<const CellGrids> grids_;
  CellStepperOptions options_;
  std::vector<double> volume0_, area0_;
  std::vector<SHCoeffs> previous_rate_;  // U of the previous step (AB2)
  Eigen::MatrixXd velocity_;
  double time_ = 0.0;
  long steps_ = 0;
};

}  // namespace rbcflow
