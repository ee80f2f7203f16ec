#pragma once
// Axisymmetric tube flow of paper section 11.1 (test_axisymmetric_tube.cpp, _slow.cpp): red
// cells on the axis of a D = 3.2 tube, centres 2 apart, lambda = 5, membrane (35). One cell in
// a 4 x 4 x 2 periodic box (square cross-section, as (45) needs) is the same periodic train.
// The effective viscosity is (46) with the exterior flux (45) (libsolver/wall/tube_flow.h),
// divided by the same quantity for the cell-free tube on the same wall mesh, so that the
// wall's discretisation error (mu_eff - 1 of order 1e-3) does not enter; the mean tube
// velocity is Q_tube / (pi a^2) = a^2 G / (8 mu_eff), G = -<dp/dz>.
// The flow is driven by <u>. Stokes flow is linear in <u> for a fixed shape, so the ratio of
// the tube velocity to <u> for the resting cell is measured once (one solve) and <u> is set
// to target / ratio: the run starts at the target tube velocity and the report gives the
// tube velocity reached at the end (it rises a little as the cell deforms and the tube's
// resistance falls).
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/vessel/vessel.h"
#include "libsolver/wall/tube_flow.h"
#include "vessel_cell_support.h"

namespace rbcflow::tube_test {

using namespace rbcflow::vessel_cell_test;

constexpr double kDiameter = 3.2, kRadius = 1.6, kSide = 4.0, kPeriod = 2.0, kLambda = 5.0;
inline const Eigen::Vector3d kBox(kSide, kSide, kPeriod);
inline const Eigen::Vector3d kAxisPoint(0.5 * kSide, 0.5 * kSide, 0.5 * kPeriod);

inline std::shared_ptr<const WallElements> tube_wall(double element_size) {
  TubeSpec spec;
  spec.diameter = kDiameter;
  spec.axis = 2;
  spec.box = kBox;
  spec.element_size = element_size;
  return std::make_shared<const WallElements>(tube(spec));
}

inline CellStepperOptions tube_options(std::shared_ptr<const WallElements> wall, double mean_velocity, double dt) {
  CellStepperOptions o;
  o.dt = dt;
  o.domain = LayerDomain{PeriodicBox(kBox), 1e-6};
  o.mean_velocity = Eigen::Vector3d(0, 0, mean_velocity);
  o.viscosity_ratio = kLambda;
  o.wall = std::move(wall);
  return o;
}

inline double effective_viscosity(const Eigen::Vector3d& mean_velocity, const Eigen::Vector3d& pressure_gradient) {
  return tube_effective_viscosity(kRadius, kSide, mean_velocity.z(), pressure_gradient.z());
}

inline double tube_velocity(double mu_eff, const Eigen::Vector3d& pressure_gradient) {
  return kRadius * kRadius * (-pressure_gradient.z()) / (8 * mu_eff);
}

// (46) for the tube without cells on the same wall (one wall solve).
inline double cell_free_effective_viscosity(const std::shared_ptr<const WallElements>& wall) {
  CellStepper stepper({}, CellGrids::make(4, 4), tube_options(wall, 1.0, 1.0));  // no cells: grids unused
  const FlowSolution s = stepper.solve();
  return effective_viscosity(s.mean_velocity, s.pressure_gradient);
}

// Tube velocity / <u> with the resting cell (one solve).
inline double tube_velocity_ratio(const std::shared_ptr<const WallElements>& wall, int N, int M) {
  auto grids = CellGrids::make(N, M);
  CellStepper stepper({red_cell(N, grids, kAxisPoint)}, grids, tube_options(wall, 1.0, 1.0));
  const FlowSolution s = stepper.solve();
  return tube_velocity(effective_viscosity(s.mean_velocity, s.pressure_gradient), s.pressure_gradient);
}

struct TubeRun {
  double target = 0;           // tube velocity asked for
  bool blew_up = false;
  std::string error;
  long steps = 0;
  double time = 0;
  double mu_rel = 0;           // mu_eff / mu_eff(cell-free) at the end
  double mu_rel_start = 0;     // at the first step
  double mu_rel_change = 0;    // |change| of mu_rel over the last `steady_window` of the run
  double tube_velocity = 0;    // at the end
  double max_offset = 0;       // max over steps of the centroid's distance from the axis
  double slip = 0;             // max |u - u_centroid| / |u_centroid| over the nodes, at the end
  double max_volume_error = 0;
  double length0 = 0;             // axial extent of the resting cell
  double length = 0, radius = 0;  // axial and radial extent of the cell at the end
  bool finite = true;
  double seconds = 0;
};

// A run at tube velocity `target` (<u> = target / ratio) for at most `steps` steps of dt. The
// change of mu_rel over the last `steady_window` (time) measures how steady the end is. With
// steady_slip > 0 the run stops once the slip is below it and the change of mu_rel over the
// last window below `steady_change`.
inline TubeRun run_tube(const std::shared_ptr<const WallElements>& wall, double mu_free, double ratio, int N, int M,
                        double target, double dt, long steps, double steady_window, long print_every,
                        double steady_slip = 0.0, double steady_change = 0.0, bool volume_constraint = false) {
  const auto start = std::chrono::steady_clock::now();
  auto grids = CellGrids::make(N, M);
  CellStepperOptions options = tube_options(wall, target / ratio, dt);
  options.volume_constraint = volume_constraint;
  CellStepper stepper({red_cell(N, grids, kAxisPoint)}, grids, options);
  TubeRun r;
  r.target = target;
  const Eigen::MatrixXd x0 = cell_nodes(stepper);
  r.length0 = x0.col(2).maxCoeff() - x0.col(2).minCoeff();
  const long window = std::max(1L, std::lround(steady_window / dt));
  std::vector<double> history;
  std::printf("tube velocity %.2f (<u> = %.3f), N = %d, M = %d, dt = %.3e, %ld steps\n", target, target / ratio, N, M,
              dt, steps);
  std::printf("  step  t       mu_eff/mu_0  U_tube  offset    slip     length  radius  V/V0-1     cell/wall GMRES  s\n");
  for (long n = 1; n <= steps; ++n) {
    const FlowSolution s = [&] {
      try {
        return stepper.solve();
      } catch (const std::runtime_error& e) {
        r.blew_up = true;
        r.error = e.what();
        return FlowSolution{};
      }
    }();
    if (r.blew_up) break;
    // The state solved for (X^n): its mu_eff and the membrane's motion relative to the centroid.
    const double mu_rel = effective_viscosity(s.mean_velocity, s.pressure_gradient) / mu_free;
    const Eigen::RowVector3d uc = s.velocity.colwise().mean();
    r.slip = (s.velocity.rowwise() - uc).rowwise().norm().maxCoeff() / uc.norm();
    r.tube_velocity = tube_velocity(mu_rel * mu_free, s.pressure_gradient);
    r.finite = r.finite && s.velocity.allFinite() && std::isfinite(mu_rel);
    if (n == 1) r.mu_rel_start = mu_rel;
    history.push_back(mu_rel);
    r.mu_rel = mu_rel;
    StepReport rep;
    try {
      rep = stepper.advance(s);
    } catch (const std::runtime_error& e) {
      r.blew_up = true;
      r.error = e.what();
      break;
    }
    r.max_volume_error = std::max(r.max_volume_error, rep.max_volume_error);
    const Eigen::MatrixXd x = cell_nodes(stepper);
    r.finite = r.finite && x.allFinite();
    const Eigen::Vector3d c = cell_centroid(stepper);
    r.max_offset = std::max(r.max_offset, std::hypot(c.x() - kAxisPoint.x(), c.y() - kAxisPoint.y()));
    r.length = x.col(2).maxCoeff() - x.col(2).minCoeff();
    r.radius = ((x.col(0).array() - kAxisPoint.x()).square() + (x.col(1).array() - kAxisPoint.y()).square())
                   .sqrt()
                   .maxCoeff();
    r.steps = n;
    const bool steady = steady_slip > 0 && r.slip < steady_slip && n > window &&
                        std::abs(mu_rel - history[history.size() - 1 - window]) < steady_change;
    if (n % print_every == 0 || n == steps || steady) {
      std::printf("  %4ld  %.4f  %.5f      %.3f   %.2e  %.2e  %.3f   %.3f   %+.2e  %d / %d          %.0f\n", n,
                  stepper.time(), mu_rel, r.tube_velocity, r.max_offset, r.slip, r.length, r.radius,
                  rep.max_volume_error, rep.gmres_iterations, rep.gmres_wall, seconds_since(start));
      std::fflush(stdout);
    }
    if (steady) break;
  }
  if (r.blew_up) std::printf("  stopped at t = %.4f: %s\n", stepper.time(), r.error.c_str());
  if (history.size() > static_cast<std::size_t>(window)) {
    r.mu_rel_change = std::abs(history.back() - history[history.size() - 1 - window]);
  }
  r.time = stepper.time();
  r.seconds = seconds_since(start);
  return r;
}

}  // namespace rbcflow::tube_test
