#pragma once
// A tilted red cell in free-space shear with and without de-aliasing (test_dealiasing.cpp,
// test_dealiasing_slow.cpp): the runs and the spectra tables (44).
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow::dealiasing_test {


struct CellRun {
  int dealias_order = 0;
  bool blew_up = false;
  std::string error;
  std::vector<double> times;
  std::vector<Eigen::VectorXd> spectra;  // eq. (44) at each record
};

inline CellRun run_red_cell_in_shear(int N, int M, double dt, double t_end, double record_every) {
  auto grids = CellGrids::make(N, M);
  Cell cell;
  cell.shape = make_biconcave(N);
  cell.shape.rotate(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix());
  cell.membrane = std::make_shared<const Membrane>(
      cell.shape, grids, MembraneParameters{std::make_shared<SkalakLaw>(12.4, 200.0), 0.0669});
  CellStepperOptions o;
  o.dt = dt;
  o.background = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.z(), 0, 0); };
  CellStepper stepper({cell}, grids, o);
  CellRun r;
  r.dealias_order = M;
  const long steps = std::lround(t_end / dt), every = std::lround(record_every / dt);
  for (long n = 1; n <= steps; ++n) {
    try {
      stepper.step();
    } catch (const std::runtime_error& e) {
      r.blew_up = true;
      r.error = e.what();
      std::printf("  M = %d stopped at t = %.4f: %s\n", M, stepper.time(), e.what());
      break;
    }
    if (n % every == 0) {
      r.times.push_back(stepper.time());
      r.spectra.push_back(stepper.cells()[0].shape.coeffs().spectrum());
    }
  }
  return r;
}

// Top-mode energy E_{N-1} of both runs in time, and the final spectra side by side.
inline void print_tables(const CellRun& plain, const CellRun& dealiased, int N) {
  std::printf("  t       E_%d (M = %d)  E_%d (M = %d)  ratio\n", N - 1, plain.dealias_order, N - 1,
              dealiased.dealias_order);
  for (std::size_t i = 0; i < dealiased.times.size(); ++i) {
    const double a = i < plain.spectra.size() ? plain.spectra[i][N - 1] : NAN, b = dealiased.spectra[i][N - 1];
    std::printf("  %.3f   %.4e        %.4e        %.2f\n", dealiased.times[i], a, b, a / b);
  }
  const std::size_t last = std::min(plain.spectra.size(), dealiased.spectra.size()) - 1;
  std::printf("  spectra (44) at t = %.3f\n  n    E_n (M = %d)  E_n (M = %d)  ratio\n", dealiased.times[last],
              plain.dealias_order, dealiased.dealias_order);
  for (int n = 0; n < N; ++n) {
    const double a = plain.spectra[last][n], b = dealiased.spectra[last][n];
    std::printf("  %2d   %.4e    %.4e    %.3f\n", n, a, b, a / b);
  }
}

}  // namespace rbcflow::dealiasing_test
