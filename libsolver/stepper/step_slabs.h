#pragma once
// This rank's slabs of the grids split over the ranks that a step's operators with the cells use
// besides the cells' own layers (CellLayers): the layers at the wall nodes (for (12)), at the flux
// sections' points, and the wall's operator at the cell nodes (for (10)). They are known before
// the operators are built, from the counts each grid is chosen by (spme_grid_cache.h): with the
// layers' own slabs they name the step's halo (CellLayers::halo_with) before any operator is
// built. check_built_slabs then holds each built operator to them, so that a grid chosen other
// than foreseen is an error, not a halo that silently misses cells.
#include <optional>
#include <string>
#include <vector>

#include "libsolver/operators/cell_layers.h"
#include "libsolver/spme/spme_grid_cache.h"
#include "wall_coupling.h"

namespace rbcflow {

// The operators of a step with cells, as the stepper builds them.
struct StepOperators {
  long cell_nodes = 0;                // of all the cells
  bool with_double_layer = false;     // lambda != 1
  const WallCoupling* wall = nullptr;  // null: no wall
  bool sections = false;              // flux sections measured with the cells
  // The points of the chosen sections (SectionFluxMeter::points_per_step); none: not known
  // before they are chosen, and the sections' slab is taken as every plane (every cell).
  std::optional<long> section_points;
};

// This rank's slabs of the step's other operators' grids (none in free space or on one rank).
// Collective: every rank asks for the same grids (from `cell_grid_cache` and the wall's cache).
std::vector<SlabPlanes> step_slabs(const LayerDomain& domain, const StepOperators& operators,
                                   SpmeGridCache* cell_grid_cache);

// Throws std::logic_error naming `what` where a slab of `built` is not among `foreseen` (which
// may hold a slab of every plane, which every slab is within).
void check_built_slabs(const std::vector<SlabPlanes>& built, const std::vector<SlabPlanes>& foreseen,
                       const std::string& what);

}  // namespace rbcflow
