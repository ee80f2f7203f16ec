#pragma once
// The cell-free layer of a straight tube: the plasma layer between the wall and the outer edge
// of the cells' core. The edge is taken, as in simulations of blood in tubes (Fedosov et al.,
// Biophys. J. 98, 2010), from the cells' membranes: the tube's period is divided into slices
// along the axis and sectors about it, the edge in each bin is the largest distance from the
// axis of a membrane point in it, and the layer is the radius less that edge, averaged over the
// bins that hold a membrane point (single-file cells leave bins between them empty).
#include <vector>

#include "geometry/sph/sph_transform.h"
#include "geometry/surface/sh_surface.h"
#include "libsolver/parallel/communicator.h"
#include "libsolver/stepper/tube_drive.h"

namespace rbcflow {

struct CellFreeLayerBins {
  double slice_length = 0.5;  // along the axis, in a (rounded to divide the period)
  int sectors = 16;
};

// `cells`: this rank's cells (every cell on one rank); `period`: the tube's period along its
// axis. On several `ranks` each bins the points of its cells and the edges are the ranks'
// largest: the same as one rank with every cell. Throws std::invalid_argument where no rank
// has a cell or for bins that are not positive. Collective.
double cell_free_layer(const std::vector<SHSurface>& cells, const SHTransform& grid, const TubeSection& tube,
                       double period, const CellFreeLayerBins& bins = {}, const Communicator& ranks = {});

}  // namespace rbcflow
