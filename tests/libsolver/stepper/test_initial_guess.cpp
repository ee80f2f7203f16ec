// The GMRES initial guesses of a step (cell_stepper.h StepperState): the quadratic extrapolation
// 3 U^{n-1} - 3 U^{n-2} + U^{n-3} is O(dt^3) from U^n, the linear 2 U^{n-1} - U^{n-2} O(dt^2)
// and U^{n-1} alone O(dt), so the cell solve of a lambda != 1 run needs fewer iterations with
// each; the solution is the same to the GMRES tolerance.
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "geometry/surface/reference_shapes.h"
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

// Steps the run with a history of `kept` velocities (1: U^{n-1}, 2: and U^{n-2}, 3: and U^{n-3})
// and returns the GMRES iterations of steps 4-8, where the full history exists.
int iterations_with_history(CellStepper& stepper, int kept) {
  int total = 0;
  for (int step = 1; step <= 8; ++step) {
    StepperState s = stepper.state();
    if (kept < 3) s.oldest_velocity.resize(0, 3);
    if (kept < 2) s.older_velocity.resize(0, 3);
    stepper.restore(s);
    const int n = stepper.step().gmres_iterations;
    if (step >= 4) total += n;
  }
  return total;
}

}  // namespace

TEST(InitialGuess, EachOrderOfExtrapolationSavesIterationsAndKeepsTheSolution) {
  CellStepper quadratic = sheared_cell(), linear = sheared_cell(), plain = sheared_cell();
  const int q = iterations_with_history(quadratic, 3);
  const int l = iterations_with_history(linear, 2);
  const int p = iterations_with_history(plain, 1);
  std::printf("  GMRES iterations over steps 4-8: %d quadratic, %d linear, %d from U^{n-1}\n", q, l, p);
  EXPECT_LT(q, l);
  EXPECT_LT(l, p);
  // All solve to 1e-8; the shapes after 8 steps of dt = 1e-3 agree to far below that.
  const Eigen::MatrixXd& x = quadratic.cells()[0].shape.coeffs().values();
  for (const CellStepper* other : {&linear, &plain}) {
    const Eigen::MatrixXd& y = other->cells()[0].shape.coeffs().values();
    EXPECT_LT((x - y).norm(), 1e-8 * x.norm());
  }
}

TEST(InitialGuess, RestoreRejectsAnEarlierVelocityOfAnotherSize) {
  CellStepper stepper = sheared_cell();
  stepper.step();
  for (auto field : {&StepperState::older_velocity, &StepperState::oldest_velocity}) {
    StepperState s = stepper.state();
    s.*field = Eigen::MatrixXd::Zero(7, 3);
    EXPECT_THROW(stepper.restore(s), std::invalid_argument);
  }
}
