#pragma once
// Kinematic collision removal of section 11.2: after a position update, every cell surface
// point x closer than h_s to another cell (or to the vessel wall) is moved along the direction
// from its projection x_p on that surface until |x - x_p| = h_s; the cell's order-N spherical
// harmonic displacement is fitted to these pushes at the pushed grid points, so the cell stays
// a smooth order-N surface. A push moves the points around it too, and may bring others
// within h_s, so detection and push are repeated until no point is closer than h_s (or
// `max_iterations` passes).
//
// Choices where the paper is silent (docs/method-notes.md):
// - a cell-cell push is shared so that the pair ends h_s apart (moving both the whole way
//   would leave 2 h_s - d): each side takes D_self / (D_self + D_other) of h_s - d, D the
//   largest deficit its grid points find: half each for two smooth surfaces, all of it for a
//   tip whose neighbour's grid points straddle it; the wall takes none;
// - the distance is to the spectral surface itself (Gauss-Newton projection seeded by the AABB
//   tree over the grid triangulation), not to the triangulation, whose chord sag at N = 16 is
//   of the order of h_s;
// - points are pushed to h_s (1 + 1%) so that the repeated passes end at or just above h_s;
// - periodic images of every cell, itself included, are tested.
#include <Eigen/Core>
#include <vector>

#include "geometry/surface/sh_surface.h"
#include "geometry/sph/sph_transform.h"
#include "geometry/contact/wall_distance.h"
#include "libsolver/parallel/communicator.h"

namespace rbcflow {

struct CollisionReport {
  int cell_pairs = 0;             // pairs of cells (periodic images included) found closer than h_s
  int wall_contacts = 0;          // cells found closer than h_s to the wall
  double max_overlap = 0.0;       // h_s - (smallest separation found), before the removal; 0 if none
  double max_displacement = 0.0;  // largest displacement of a grid point, all passes together
  double min_separation = 0.0;    // smallest point-surface separation after the removal (cells
                                  // and wall; +infinity when nothing came within 2 h_s)
  int closest_cell = -1;          // the cell of a point at min_separation (-1: none), and the
  int closest_other = -1;         // cell or wall (-1) it is that close to
  int passes = 0;                 // detection passes that moved something
  bool converged = true;          // no point closer than h_s after the last pass
  int shapes_brought = 0;         // other ranks' cells' shapes brought to this rank, all passes
};

// Moves the points of `cells` (grid of `grid_transform`: the paper's N x 2N grid, or a finer
// one whose points are then the tested surface points; the correction is analysed at each
// cell's own order) apart to separation `threshold`. `period`: box sides of the periodic
// directions, 0 where not periodic. `wall` may be null. Cells with nothing closer than
// `threshold` are left bit-identical. On several `ranks` each rank finds and fits the pushes of
// its block of the cells (owned_block) and reads only the shapes of that block and of the
// cells near it: the blocks' bounding spheres are shared at each pass and the shapes of the
// others' cells within reach of its own brought from their ranks (share_blocks.h's
// bring_items), and a pair's deficit on one side sent to the other side's rank where two
// ranks push its cells. Only the rank's block need be current on entry (the other shapes are
// not read before they are brought); on return its block holds the same bits as one rank's
// run, the other shapes as last brought (the caller shares the blocks), and the report is the
// same on every rank.
CollisionReport remove_collisions(std::vector<SHSurface>& cells, const SHTransform& grid_transform,
                                  const Eigen::Vector3d& period, const WallDistance* wall, double threshold,
                                  const Communicator& ranks = {}, int max_iterations = 20);

}  // namespace rbcflow
