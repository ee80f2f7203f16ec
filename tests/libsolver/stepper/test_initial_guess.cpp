// The GMRES initial guesses of a step (cell_stepper.h StepperState): the linear extrapolation
// 2 U^{n-1} - U^{n-2} is O(dt^2) from U^n where U^{n-1} is O(dt), so the cell solve of a lambda
// != 1 run needs fewer iterations; the solution is the same to the GMRES tolerance.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "geometry/reference_shapes.h"
#include "libsolver/membrane/membrane_law.h"
#include "libsolver/stepper/cell_stepper.h"

using namespace rbcflow;

namespace {

// A red cell inclined in simple shear, lambda = 5, free space.
CellStepper sheared_cell() {
  auto grids = CellGrids::make(12, 24);
  SHSurface s = make_biconcave(12);
  s.rotate(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), Eigen::Vector3d(1, 0, 1).normalized())
               .toRotationMatrix());
  Cell c;
  c.membrane = std::make_shared<const Membrane>(s, grids, MembraneParameters{make_membrane_law("skalak", 12.4, 200.0), 0.0669});
  c.shape = s;
  CellStepperOptions o;
  o.dt = 1e-3;
  o.viscosity_ratio = 5.0;
  o.gmres_tolerance = 1e-8;
  o.background = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.z(), 0, 0); };
  return CellStepper({c}, grids, o);
}

}  // namespace

TEST(InitialGuess, ExtrapolationSavesIterationsAndKeepsTheSolution) {
  CellStepper extrapolating = sheared_cell(), plain = sheared_cell();
  int with = 0, without = 0;
  for (int step = 1; step <= 6; ++step) {
    const int a = extrapolating.step().gmres_iterations;
    // The plain run forgets U^{n-2} before each step, so its guess is U^{n-1}.
    StepperState s = plain.state();
    s.older_velocity.resize(0, 3);
    plain.restore(s);
    const int b = plain.step().gmres_iterations;
    if (step >= 3) with += a, without += b;  // steps 1 and 2 have no U^{n-2} in either run
  }
  std::printf("  GMRES iterations over steps 3-6: %d extrapolated, %d from U^{n-1}\n", with, without);
  EXPECT_LT(with, without);
  // Both solve to 1e-8; the shapes after 6 steps of dt = 1e-3 agree to far below that.
  const Eigen::MatrixXd& x = extrapolating.cells()[0].shape.coeffs().values();
  const Eigen::MatrixXd& y = plain.cells()[0].shape.coeffs().values();
  EXPECT_LT((x - y).norm(), 1e-8 * x.norm());
}

TEST(InitialGuess, RestoreRejectsAnOlderVelocityOfAnotherSize) {
  CellStepper stepper = sheared_cell();
  stepper.step();
  StepperState s = stepper.state();
  s.older_velocity = Eigen::MatrixXd::Zero(7, 3);
  EXPECT_THROW(stepper.restore(s), std::invalid_argument);
}
