#pragma once
// The initial cells of a case: listed (cells.positions, each turned to its orientation) or
// placed at random (cells.count, or cells.hematocrit of the meshed lumen; pre-deformed in tubes
// narrower than a cell, geometry/contact/cell_placement.h), the perturbation of section 9 applied, and
// every cell checked, as it will start, against the box, the vessel wall and the other cells
// through geometry's one overlap test (geometry/contact/cell_overlap.h).
#include <optional>
#include <string>
#include <vector>

#include "geometry/surface/sh_surface.h"
#include "geometry/vessel/vessel_mesh.h"
#include "io/case.h"

namespace rbcflow {

// The reference shape of `cells` centred at the origin, order `order`.
SHSurface reference_shape(const CaseCells& cells, int order);

// The symmetry axis of each listed cell (unit vectors): `orientations`, or uniformly random
// directions from `seed` (the same on every machine) when none are given.
std::vector<Vec3> cell_orientations(const CaseCells& cells);

// One surface per entry of `positions`, at order `order`.
std::vector<SHSurface> placed_cells(const CaseCells& cells, int order);

// The smallest cell-cell and cell-wall distance of cells placed at random: the collision
// threshold h_s, and at least 0.05.
double placement_gap(const Case& c);

struct InitialCells {
  // The membranes' reference shapes: rigid motions (rotation and translation of the
  // coefficients) of reference_shape(cells, cells.order), so that they share its rest metrics.
  std::vector<SHSurface> rest;
  std::vector<SHSurface> initial;  // the shapes the run starts from (perturbed, pre-deformed)
  std::optional<std::string> note;  // how the cells were placed, where it is not plain
};

// The cells of `c` at order cells.order inside `vessel` (may be null). Throws CaseError naming
// cells.positions and the cell's index when a listed cell is longer than the periodic box,
// reaches through the vessel wall or within the collision threshold h_s of it, or overlaps
// another cell (or a periodic image); naming cells.count / cells.hematocrit when the cells
// cannot be placed. Cells placed at random and then perturbed are checked the same way.
InitialCells initial_cells(const Case& c, const VesselMesh* vessel);

}  // namespace rbcflow
