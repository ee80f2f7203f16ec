#pragma once
// Wall-clock seconds spent in each part of one CellStepper::solve() (FlowSolution::timings),
// for bench/bench_step.cpp and docs/performance.md. Measuring changes no result.
#include "libsolver/common/scoped_timer.h"

namespace rbcflow {

struct StepTimings {
  double membrane = 0.0;          // traction of every cell, eq. (22)-(23)
  double cell_geometry = 0.0;     // quadrature geometry of the cells and their Ewald plans
  double self_corrections = 0.0;  // singular corrections, one per cell (section 5.4)
  double near_corrections = 0.0;  // near-target search and nearly-singular corrections
  double at_wall_build = 0.0;     // the cells' layers at the wall nodes (CellLayersAtPoints)
  double wall_at_cells_build = 0.0;  // the wall operator with the cell nodes as targets
  double cell_products = 0.0;     // cell-cell single and double layer products (10)
  double cell_corrections = 0.0;  // of which: the singular and nearly-singular corrections applied
  // of which, the double layer's Ewald sums (this rank's part): real-space pairs, SPME spreading,
  // transforms (with the influence function) and interpolation
  double cell_ewald_real = 0.0, cell_ewald_spreading = 0.0, cell_ewald_fft = 0.0, cell_ewald_interpolation = 0.0;
  double at_wall_products = 0.0;  // the cells' layers evaluated at the wall nodes (12)
  double wall_solve = 0.0;        // GMRES of (12)
  double wall_at_cells = 0.0;     // the wall's velocity at the cell nodes
  double total = 0.0;             // all of solve()
};

}  // namespace rbcflow
