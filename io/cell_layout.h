#pragma once
// The initial cells of a case that lists their positions: the reference shape (symmetry axis
// along z) turned to each orientation and moved to each position; and the check that they
// fit the box and the vessel and do not overlap. Cells placed at random (count or hematocrit
// without positions) are placed by the run itself.
#include <vector>

#include "geometry/sh_surface.h"
#include "io/case.h"

namespace rbcflow {

// The reference shape of `cells` centred at the origin, order `order`.
SHSurface reference_shape(const CaseCells& cells, int order);

// The symmetry axis of each listed cell (unit vectors): `orientations`, or uniformly random
// directions from `seed` (the same on every machine) when none are given.
std::vector<Vec3> cell_orientations(const CaseCells& cells);

// One surface per entry of `positions`, at order `order`.
std::vector<SHSurface> placed_cells(const CaseCells& cells, int order);

// Throws CaseError (naming cells.positions and its line) when a listed cell is longer than the
// periodic box, crosses the wall of a tube or constriction, or overlaps another cell (or a
// periodic image of it). Tested on a triangulation of order 8; touching within that
// resolution is not an overlap.
void check_cell_layout(const Case& c);

}  // namespace rbcflow
