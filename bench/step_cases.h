#pragma once
// The cases of the step benchmark, read from case files and prepared as rbcflow run prepares
// them (scenario/scenario.h; no output is written):
//   single:   bench/cases/single.toml: one red cell in free-space shear flow (rate 1), N = 16,
//             M = 48, lambda = 5;
//   minicase: bench/cases/minicase.toml: 2 red cells, N = 12, M = 36, lambda = 1, in a D = 10
//             tube of ~2,400 triangles, box 10.5 x 10.5 x 8, <u> = e_z, Ewald tolerance 1e-6,
//             wall solve to 1e-6;
//   tube27:   data/cases/tube_27_cells.toml, read and prepared as rbcflow run does: 27 red
//             cells (tube hematocrit 0.30, seed 1), N = 16, M = 48, lambda = 5, D = 6 tube
//             (h = 0.25), box 6.6 x 6.6 x 13.33, <u> = 5 e_z, Ewald and GMRES tolerances 1e-6,
//             collisions h_s = 0.02, volume constraint;
//   tubeK:    the same case with K cells in a period of 13.33 K / 27 (fixed hematocrit, e.g.
//             tube8, tube125: the growth series);
//   wideK:    data/cases/tube_1000_cells.toml (D = 12, h = 0.4, otherwise as tube27) with K
//             cells in a period of 123.56 K / 1000 (e.g. wide125, wide512);
//   CASE.toml: any case file, prepared as rbcflow run prepares it, with its own time step.
// Membranes: Skalak with bending, the paper's parameters (35). dt = 1e-3 (about the "auto"
// step (37) of these cases; the cost of a step hardly depends on it); a case file keeps its own.
#include <memory>
#include <string>

#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow::bench {

struct StepCase {
  std::unique_ptr<CellStepper> stepper;
  double estimated_peak_bytes = 0;  // rbcflow check's memory model (scenario/memory_budget.h)
};

// Throws std::invalid_argument for an unknown name. memory_gib > 0 replaces the case's
// solver.memory_gib (the budget that chooses the run's memory modes, scenario/memory_budget.h):
// e.g. wide125 with 2.6 runs in the modes the 1,000 cells take on this machine.
StepCase make_step_case(const std::string& name, double memory_gib = 0);

}  // namespace rbcflow::bench
