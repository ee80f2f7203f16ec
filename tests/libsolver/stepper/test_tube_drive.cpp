// The tube velocity drive (libsolver/stepper/tube_drive.h): in a straight periodic tube the
// ratio of the tube's mean velocity to the box mean <u> is known in closed form from eq. (45):
// with G = -<dp/dz>, the flux inside is Q_tube = pi a^4 G / 8 (Poiseuille) and outside
// Q_ext = G L^4 / (4 pi) F(chi); their sum is L^2 <u>, so
//   U_tube / <u> = (a^2 G / 8) / <u> = a^2 L^2 / 8 / (pi a^4 / 8 + L^4 F(chi) / (4 pi)).
// The measured ratio comes from the velocity on the axis of the discretised wall, so it
// converges with the wall's element size (linear elements: second order).
// Measured: exact 0.778450; h = D/8 0.768490 (1.28e-2), h = D/16 0.775858 (3.33e-3), order 1.94.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "geometry/vessel/vessel.h"
#include "libsolver/stepper/cell_stepper.h"
#include "libsolver/stepper/tube_drive.h"
#include "libsolver/wall/tube_flow.h"

using namespace rbcflow;

namespace {

constexpr double kD = 3.5, kSide = 5.0, kLength = 3.0;

const Eigen::Vector3d kBox(kSide, kSide, kLength);

std::shared_ptr<const WallElements> tube_wall(double h) {
  TubeSpec spec;
  spec.diameter = kD;
  spec.box = kBox;
  spec.element_size = h;
  return std::make_shared<const WallElements>(tube(spec));
}

double measured_ratio(double h) {
  WallCoupling coupling(tube_wall(h), PeriodicBox(kBox), 1e-8, WallSolveOptions{1e-9, 300, 60});
  return tube_velocity_per_mean_velocity(coupling, Eigen::Vector3d(0.5 * kSide, 0.5 * kSide, 0.3 * kLength), 2);
}

}  // namespace

TEST(TubeDrive, StraightTubeRatioMatchesEquation45) {
  const double a = 0.5 * kD, pi = std::numbers::pi;
  const double F = exterior_flux_factor(pi * a * a / (kSide * kSide));
  const double exact = a * a * kSide * kSide / 8.0 / (pi * std::pow(a, 4) / 8.0 + std::pow(kSide, 4) * F / (4 * pi));
  const double coarse = measured_ratio(kD / 8), fine = measured_ratio(kD / 16);
  const double e_coarse = std::abs(coarse / exact - 1), e_fine = std::abs(fine / exact - 1);
  std::printf("U_tube / <u>: exact %.6f, h = D/8 %.6f (rel. error %.2e), h = D/16 %.6f (%.2e), order %.2f\n", exact,
              coarse, e_coarse, fine, e_fine, std::log2(e_coarse / e_fine));
  EXPECT_LT(e_fine, 5e-3);
  EXPECT_GT(std::log2(e_coarse / e_fine), 1.5);  // linear elements: second order in h
}

TEST(TubeDrive, RejectsAnAxisOutsideTheBox) {
  WallCoupling coupling(tube_wall(kD / 6), PeriodicBox(kBox), 1e-6, WallSolveOptions{});
  EXPECT_THROW(tube_velocity_per_mean_velocity(coupling, Eigen::Vector3d(2.5, 2.5, 1.0), 3), std::invalid_argument);
}

TEST(TubeDrive, StepperSetsTheMeanVelocityFromTheTubeVelocity) {
  const auto wall = tube_wall(kD / 6);
  const Eigen::Vector3d axis_point(0.5 * kSide, 0.5 * kSide, 0.0);
  WallCoupling coupling(wall, PeriodicBox(kBox), 1e-6, WallSolveOptions{});
  const double ratio = tube_velocity_per_mean_velocity(coupling, axis_point, 2);

  CellStepperOptions o;
  o.domain = LayerDomain{PeriodicBox(kBox), 1e-6};
  o.wall = wall;
  o.tube_drive = TubeDrive{1.5, axis_point, 2};
  const CellStepper stepper({}, CellGrids::make(4, 4), o);
  EXPECT_NEAR(stepper.mean_velocity().z(), 1.5 / ratio, 1e-9 / ratio);
  EXPECT_EQ(stepper.mean_velocity().x(), 0.0);
  EXPECT_EQ(stepper.mean_velocity().y(), 0.0);

  o.pressure_gradient = Eigen::Vector3d(0, 0, -1);
  EXPECT_THROW(CellStepper({}, CellGrids::make(4, 4), o), std::invalid_argument);
}
