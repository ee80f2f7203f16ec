#pragma once
// From a case to a ready stepper: the vessel meshed, the cells built (reference shape, placed,
// perturbed), their membranes, the domain and the time step. The one place where the case's
// keys meet libsolver's options.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/case.h"
#include "libsolver/stepper/cell_stepper.h"

namespace rbcflow::cli {

struct RunSetup {
  std::shared_ptr<const CellGrids> grids;
  std::vector<Cell> cells;
  std::shared_ptr<const WallElements> wall;  // null without a vessel
  CellStepperOptions options;
  long steps = 0;  // to reach time.end
  std::optional<double> tube_radius;  // a straight tube: for (45)-(46)
  std::optional<std::string> placement_note;  // printed by run: cells placed pre-deformed
};

// Throws CaseError for what only shows once meshed or placed (cells outside the vessel).
RunSetup setup_run(const Case& c);

// The smallest cell-cell and cell-wall distance of cells placed at random: the collision
// threshold h_s, and at least 0.05.
double placement_gap(const Case& c);

}  // namespace rbcflow::cli
