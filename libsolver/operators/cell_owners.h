#pragma once
// Which rank owns which cell in a step's layer products (cell_layers.h). The owner of a cell
// builds its quadrature corrections and sums its nodes as sources; the GMRES of (10) keeps its
// rows (parallel/owned_rows.h). On a grid split into slabs over the ranks (spme/spme_grid.h)
// the cells are taken along the slab axis by their positions (the mean of their nodes, in
// [0, L) of the box) and cut into the ranks' blocks of equal counts (owned_block's sizes), rank
// 0 the lowest, as the grid's slabs are: a rank's cells are then a length of a tube, near the
// slab of the grid it spreads into, and the ranks hold equal shares of the corrections, the
// largest memory of a step (cutting at the slabs' planes instead left tube27's ranks 15 and 12
// cells). Recomputed every step as the cells move. Elsewhere (one rank, free space, a grid every
// rank holds whole) the owners are equal blocks of the cell indices (parallel/ownership.h).
//
// The products take the cells in owner order, so that each rank's cells are one block:
// stacked node data go into that order before a product and back after it.
#include <Eigen/Core>
#include <vector>

#include "geometry/sph/sph_coeffs.h"
#include "geometry/surface/cell_grids.h"
#include "libsolver/operators/cell_layers.h"

namespace rbcflow {

struct CellOwners {
  std::vector<int> order;  // the cells in owner order: rank 0's, then rank 1's, ...; each rank's by index
  std::vector<int> first;  // ranks + 1 positions in `order`: rank r owns order[first[r]] .. order[first[r + 1] - 1]

  bool in_cell_order() const;  // order is 0, 1, 2, ...
  // Stacked node data (nodes_per_cell rows a cell) from cell order into owner order, and back.
  Eigen::MatrixXd to_owner_order(const Eigen::MatrixXd& stacked, int nodes_per_cell) const;
  Eigen::MatrixXd to_cell_order(const Eigen::MatrixXd& stacked, int nodes_per_cell) const;
  template <class T>
  std::vector<T> to_owner_order(const std::vector<T>& per_cell) const {
    std::vector<T> out;
    out.reserve(per_cell.size());
    for (int c : order) out.push_back(per_cell[static_cast<std::size_t>(c)]);
    return out;
  }
};

// owned_block's blocks of the cells in their own order.
CellOwners owners_by_block(int cells, int ranks);
// The cells by their coordinate modulo `length` (ties by index), cut into owned_block's sizes:
// rank 0 the lowest. Throws std::invalid_argument for a coordinate that is not finite.
CellOwners owners_along(const std::vector<double>& coordinate, double length, int ranks);

// The owners of a step's products of the cells whose node spheres (cell_sphere, cell_halo.h)
// are `spheres`, nodes_per_cell nodes each (in the domain's box, on its ranks): by their
// centres along the slab axis of the grid the products spread into (the double layer's, or
// the single layer's when with_double_layer is false), taken from `grid_cache` as CellLayers
// takes it. Collective.
CellOwners cell_owners(const std::vector<CellSphere>& spheres, long nodes_per_cell, const LayerDomain& domain,
                       bool with_double_layer, SpmeGridCache* grid_cache);

// Every cell's sphere on every rank, from those of the cells `holders` gives each rank (filled
// in `spheres` by the rank that holds the cell's shape; the others' entries are overwritten):
// 5 numbers a cell gathered, where the owners once needed every shape. Collective.
void share_spheres(std::vector<CellSphere>& spheres, const CellOwners& holders, const Communicator& ranks);

}  // namespace rbcflow
