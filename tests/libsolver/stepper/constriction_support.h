#pragma once
// The constriction of paper section 10.2 (test_constriction.cpp, test_constriction_slow.cpp):
// a tube D = 3.5 along z in a 5 x 5 x 10 periodic box, necked to d(z) = 3.5 - 2.2
// exp(-1.2 (z - 5)^2) (1.3 at z = 5), one red cell (lambda = 1) starting at z = 3.25, 0.25 off
// the axis (x), its disc facing the flow, as data/cases/constriction.toml. The paper's "U = 2
// mean velocity" is taken as the tube's: <u> is set so that the cell-free flow in the wide
// section (z = 0, farthest from the neck) has mean velocity 2 (libsolver/stepper/tube_drive.h);
// a box mean <u> = 2 sends most of the flux round the outside of the tube and the cell moved
// only 0.36 per unit time.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "geometry/vessel/vessel.h"
#include "libsolver/stepper/tube_drive.h"
#include "vessel_cell_support.h"

namespace rbcflow::constriction_test {

using namespace rbcflow::vessel_cell_test;

inline const Eigen::Vector3d kBox(5.0, 5.0, 10.0);
inline const Eigen::Vector3d kStart(2.75, 2.5, 3.25);
constexpr double kTubeVelocity = 2.0;

inline ConstrictionSpec constriction_spec(double element_size) {
  ConstrictionSpec spec;
  spec.tube.diameter = 3.5;
  spec.tube.axis = 2;
  spec.tube.box = kBox;
  spec.tube.element_size = element_size;
  spec.depth = 2.2;
  spec.width = 1.2;
  spec.centre = 5.0;
  return spec;
}

struct ConstrictionRun {
  bool blew_up = false;
  std::string error;
  long steps = 0;
  double time = 0;
  double max_volume_error = 0;       // max over steps of |V / V0 - 1|
  double final_volume_change = 0;    // V / V0 - 1 at the end (signed)
  double min_volume_change = 0, max_volume_change = 0;  // extremes of V / V0 - 1 over the run
  double max_area_error = 0;
  double max_wall_fraction = 0;      // max over steps and nodes of r / (d(z) / 2)
  bool finite = true;                // every node and velocity finite throughout
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();  // centroid
  double max_gmres_wall = 0;
  double mean_velocity = 0;          // <u>_z that drives the tube at kTubeVelocity
  double seconds = 0;
  int triangles = 0;
};

// r / (d(z) / 2) for the worst node of the cell: below 1 while the cell is inside the vessel.
inline double wall_fraction(const Eigen::MatrixXd& x, const ConstrictionSpec& spec) {
  double worst = 0;
  for (int p = 0; p < x.rows(); ++p) {
    const double z = x(p, 2) - kBox.z() * std::floor(x(p, 2) / kBox.z());
    const double r = std::hypot(x(p, 0) - 0.5 * kBox.x(), x(p, 1) - 0.5 * kBox.y());
    worst = std::max(worst, r / (0.5 * spec.diameter(z)));
  }
  return worst;
}

// `steps` steps of dt, printing a line every `print_every` steps.
inline ConstrictionRun run_constriction(int N, int M, double element_size, double dt, long steps,
                                        bool volume_constraint, long print_every) {
  const auto start = std::chrono::steady_clock::now();
  const ConstrictionSpec spec = constriction_spec(element_size);
  auto wall = std::make_shared<const WallElements>(constriction(spec));
  auto grids = CellGrids::make(N, M);
  const PeriodicBox box(kBox);
  WallCoupling drive(wall, box, 1e-6, WallSolveOptions{});
  const double ratio = tube_velocity_per_mean_velocity(drive, Eigen::Vector3d(0.5 * kBox.x(), 0.5 * kBox.y(), 0.0), 2);
  CellStepperOptions o;
  o.dt = dt;
  o.domain = LayerDomain{box, 1e-6};
  o.mean_velocity = Eigen::Vector3d(0, 0, kTubeVelocity / ratio);
  o.viscosity_ratio = 1.0;
  o.volume_constraint = volume_constraint;
  o.wall = wall;
  CellStepper stepper({red_cell(N, grids, kStart)}, grids, o);
  ConstrictionRun r;
  r.triangles = wall->num_triangles();
  r.mean_velocity = o.mean_velocity.z();
  r.start = cell_centroid(stepper);
  r.max_wall_fraction = wall_fraction(cell_nodes(stepper), spec);
  std::printf("constraint %s, N = %d, M = %d, wall h = %.2f (%d triangles), dt = %.3e, %ld steps; "
              "<u> = %.4f for tube velocity %.1f (ratio %.4f)\n",
              volume_constraint ? "on" : "off", N, M, element_size, r.triangles, dt, steps, r.mean_velocity,
              kTubeVelocity, ratio);
  std::printf("  step  t       V/V0 - 1     centroid (x, z)      max r/R(z)  wall GMRES  s\n");
  for (long n = 1; n <= steps; ++n) {
    StepReport rep;
    try {
      rep = stepper.step();
    } catch (const std::runtime_error& e) {
      r.blew_up = true;
      r.error = e.what();
      std::printf("  stopped at t = %.4f: %s\n", stepper.time(), e.what());
      break;
    }
    const SurfaceGeometry g = stepper.cells()[0].shape.geometry(*stepper.grids().n_grid);
    const double dv = enclosed_volume(g) / stepper.initial_volumes()[0] - 1.0;
    const Eigen::MatrixXd x = cell_nodes(stepper);
    r.finite = r.finite && x.allFinite() && stepper.velocity().allFinite();
    r.max_volume_error = std::max(r.max_volume_error, rep.max_volume_error);
    r.min_volume_change = std::min(r.min_volume_change, dv);
    r.max_volume_change = std::max(r.max_volume_change, dv);
    r.final_volume_change = dv;
    r.max_area_error = std::max(r.max_area_error, rep.max_area_error);
    r.max_wall_fraction = std::max(r.max_wall_fraction, wall_fraction(x, spec));
    r.max_gmres_wall = std::max<double>(r.max_gmres_wall, rep.gmres_wall);
    r.steps = n;
    if (n % print_every == 0 || n == steps) {
      const Eigen::Vector3d c = volume_centroid(g);
      std::printf("  %4ld  %.4f  %+.3e   (%.3f, %.3f)       %.3f       %d          %.1f\n", n, stepper.time(), dv,
                  c.x(), c.z(), wall_fraction(x, spec), rep.gmres_wall, seconds_since(start));
      std::fflush(stdout);
    }
  }
  r.time = stepper.time();
  r.end = cell_centroid(stepper);
  r.seconds = seconds_since(start);
  std::printf("  %ld steps to t = %.4f in %.1f s: max |V/V0 - 1| = %.3e (extremes %+.3e, %+.3e; final %+.3e), "
              "max area error %.3e, max r/R(z) %.3f, centroid z %.3f -> %.3f\n",
              r.steps, r.time, r.seconds, r.max_volume_error, r.min_volume_change, r.max_volume_change,
              r.final_volume_change, r.max_area_error, r.max_wall_fraction, r.start.z(), r.end.z());
  return r;
}

}  // namespace rbcflow::constriction_test
