#include "step_slabs.h"

#include <algorithm>
#include <stdexcept>

#include "libsolver/operators/cell_layers_at_points.h"

namespace rbcflow {

std::vector<SlabPlanes> step_slabs(const LayerDomain& domain, const StepOperators& operators,
                                   SpmeGridCache* cell_grid_cache) {
  std::vector<SlabPlanes> slabs;
  if (!domain.box || operators.cell_nodes == 0 || domain.ranks.size() == 1) return slabs;
  auto add = [&](const SpmeGrid& grid) {
    if (const std::optional<SlabPlanes> slab = rank_slab(grid)) slabs.push_back(*slab);
  };
  // The cells' layers at `points` points (CellLayersAtPoints): the single layer's grid and the
  // double layer's.
  auto add_layers_at = [&](long points) {
    add(*cell_layers_at_points_grid(domain, EwaldKernel::stokeslet, operators.cell_nodes, points, cell_grid_cache));
    if (operators.with_double_layer)
      add(*cell_layers_at_points_grid(domain, EwaldKernel::stresslet, operators.cell_nodes, points, cell_grid_cache));
  };
  // In the stepper's order of building them: the layers at the wall, the wall at the cells,
  // the layers at the sections.
  if (operators.wall) {
    add_layers_at(operators.wall->nodes().rows());
    add(*operators.wall->grid_at(operators.cell_nodes, domain.ranks));
  }
  if (operators.sections) {
    if (operators.section_points) {
      add_layers_at(*operators.section_points);
    } else if (domain.ranks.size() > 1) {
      slabs.push_back(SlabPlanes{0, 1, 0, 1, 1});  // every plane of a one-plane grid: every cell
    }
  }
  return slabs;
}

void check_built_slabs(const std::vector<SlabPlanes>& built, const std::vector<SlabPlanes>& foreseen,
                       const std::string& what) {
  for (const SlabPlanes& slab : built) {
    const bool within = std::any_of(foreseen.begin(), foreseen.end(), [&](const SlabPlanes& f) {
      return f == slab || (f.first_plane == 0 && f.planes == f.size);
    });
    if (!within)
      throw std::logic_error("step_slabs: " + what + " took a grid split other than foreseen (planes " +
                             std::to_string(slab.first_plane) + " to " +
                             std::to_string(slab.first_plane + slab.planes) + " of " + std::to_string(slab.size) +
                             " along axis " + std::to_string(slab.axis) + ")");
  }
}

}  // namespace rbcflow
