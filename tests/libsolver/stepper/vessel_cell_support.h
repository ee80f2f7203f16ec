#pragma once
// Red cells in a vessel (test_constriction*.cpp, test_axisymmetric_tube*.cpp): the Evans-Fung
// disc with the paper's membrane (Skalak law, parameters (35): E_S = 12.4, E_D = 200,
// E_B = 0.0669), the time step limit (37), and what a run records about one cell.
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <memory>

#include "geometry/surface/reference_shapes.h"
#include "geometry/surface/sh_surface.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow::vessel_cell_test {

constexpr double kShearModulus = 12.4, kDilatationModulus = 200.0, kBendingModulus = 0.0669;

// The limit (37) with h_eff = sqrt(16.8) / N (dilatation sets it for N < 62).
inline double time_step_limit(int N) {
  const double h = std::sqrt(16.8) / N;
  return std::min(2.5 * std::pow(h, 1.2) / kDilatationModulus, 0.19 * std::pow(h, 3.2) / kBendingModulus);
}

// A resting red cell of order N with its symmetry axis along `axis`, centred at `centre`.
inline Cell red_cell(int N, const std::shared_ptr<const CellGrids>& grids, const Eigen::Vector3d& centre,
                     const Eigen::Vector3d& axis = Eigen::Vector3d::UnitZ()) {
  SHSurface s = make_biconcave(N);
  s.rotate(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis.normalized()).toRotationMatrix());
  s.translate(centre);
  Cell c;
  c.membrane = std::make_shared<const Membrane>(
      s, grids, MembraneParameters{std::make_shared<SkalakLaw>(kShearModulus, kDilatationModulus), kBendingModulus});
  c.shape = std::move(s);
  return c;
}

inline Eigen::Vector3d cell_centroid(const CellStepper& stepper, int c = 0) {
  return volume_centroid(stepper.cells()[c].shape.geometry(*stepper.grids().n_grid));
}

inline Eigen::MatrixXd cell_nodes(const CellStepper& stepper, int c = 0) {
  return stepper.grids().n_grid->synthesize(stepper.cells()[c].shape.coeffs());
}

// Seconds since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace rbcflow::vessel_cell_test
