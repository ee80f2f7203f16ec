#pragma once
// A case becomes a simulation: the one place where a case's keys meet geometry and libsolver.
// prepare_scenario() does everything a run does before its first step that can reject the case
// (the vessel meshed and checked, the cells placed, perturbed and checked against the wall and
// each other, the time step, the drive, the membrane law, the solver's options), so that
// `rbcflow check` and `rbcflow run` accept and refuse exactly the same cases; make_stepper()
// then builds what only a run needs (the wall's boundary elements, the first plans).
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "geometry/vessel/vessel_branch.h"
#include "geometry/vessel/vessel_mesh.h"
#include "io/case.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/stepper/cell_stepper.h"
#include "scenario/memory_budget.h"

namespace rbcflow {

// One Ewald sum of the run, as libsolver's chooser will set it up.
struct EwaldSum {
  std::string what;  // "cells, single layer", ...
  long nodes = 0;
  EwaldChoice choice;
};

struct Scenario {
  Case c;
  std::optional<VesselMesh> vessel;       // the meshed wall, without a vessel none
  std::optional<double> lumen_volume;     // of the meshed wall, one period
  std::shared_ptr<const CellGrids> grids;  // with cells
  std::vector<Cell> cells;                 // as they start
  CellStepperOptions options;              // the wall's elements are added by make_stepper
  long steps = 0;                          // to reach time.end
  std::optional<double> tube_radius;       // a straight tube: for (45)-(46)
  std::vector<VesselBranch> branches;      // of the vessel (vessel.h), for branches.csv
  bool branch_flow_by_meter = false;       // the one branch's flow is the tube meter's pi a^2 U
  std::optional<double> tube_hematocrit;   // the cells' volume over the lumen's, with a vessel
  std::optional<std::string> placement_note;  // cells placed pre-deformed: how
  std::vector<EwaldSum> ewald;             // in a periodic domain
  MemoryEstimate memory;                   // the run's peak on each rank, by part (memory_budget.h)
  double memory_budget = 0;                // bytes, for each rank
  int ranks_per_machine = 1;               // that share the machine's memory
  bool keeps_pair_coefficients = true;     // false: dropped to fit the budget
  bool reuses_freed_memory = true;         // false: close to the budget (memory_budget.h)
};

// Throws CaseError (exit 2) naming the key for everything that shows only once the vessel is
// meshed or the cells placed, and for a run that cannot fit its memory budget: that of the
// run's ranks (mpirun), or of `planned` ranks on this machine (`rbcflow check --ranks P`).
// `placed_at_order`: the cells are placed (and their rest shapes made) at that order and
// resampled to cells.order, as for a restart from a run of that order (checkpoint.h): the
// same cells and the same rest shapes as that run's.
Scenario prepare_scenario(const Case& c, std::optional<int> planned = std::nullopt,
                          std::optional<int> placed_at_order = std::nullopt);

// The stepper of a prepared scenario (its cells are moved into it): the wall's boundary
// elements are built here, and a tube-velocity drive's cell-free wall solve.
std::unique_ptr<CellStepper> make_stepper(Scenario& s);

}  // namespace rbcflow
