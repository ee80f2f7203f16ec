#pragma once
// The halo of a rank's cells in a step's layer products (cell_layers.h): the cells it does not
// own at whose nodes its part of a product can be nonzero, or whose densities it reads. On a
// grid split into slabs over the ranks (spme/spme_grid.h) a rank's part is its owned cells'
// nodes as sources:
//   - their real-space Ewald sums reach the nodes within the cutoff r_c of an owned node
//     (nearest periodic image, section 5.3);
//   - their nearly-singular corrections reach the nodes within an owned cell's near distance
//     of its surface (section 5.4), which lies within the cell's mesh size h of its nodes'
//     sphere;
//   - the smooth part, spread by every node whose B-spline stencil reaches the rank's planes
//     and interpolated at those nodes, reads and reaches only them (section 5.2).
// The halo is taken from bounding spheres (every node of a cell within `radius` of `center`),
// so it may hold a cell that no node of which is reached, never miss one that is. Everywhere
// else (free space, a grid every rank holds whole) a rank's part reaches every node: the halo
// is every cell it does not own.
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "geometry/sph/sph_coeffs.h"
#include "geometry/surface/cell_grids.h"
#include "libsolver/common/periodic_box.h"
#include "libsolver/parallel/ownership.h"
#include "libsolver/spme/spme_grid.h"

namespace rbcflow {

struct CellSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0.0;
  double area = 0.0;  // of the cell's surface on the N grid (cell_sphere; its mesh size h = sqrt(area) / N)
};

// The sphere about the mean of the nodes (rows x 3; each coordinate's mean, column by column)
// through the farthest node.
CellSphere bounding_sphere(const Eigen::MatrixXd& nodes);
// The sphere of a cell's nodes on the N grid and the cell's area there: what a rank that holds
// its shape tells the others of it (cell_owners.h), 5 numbers instead of the shape's
// coefficients.
CellSphere cell_sphere(const SHCoeffs& shape, const CellGrids& grids);

// One rank's planes of a grid split into slabs: planes [first_plane, first_plane + planes) of
// the grid's `size` planes along box axis `axis`, B-splines of order `order`.
struct SlabPlanes {
  int axis = 0, size = 0, first_plane = 0, planes = 0, order = 0;
  friend bool operator==(const SlabPlanes&, const SlabPlanes&) = default;
};

// This rank's planes of `grid`, or none where every rank holds it whole.
std::optional<SlabPlanes> rank_slab(const SpmeGrid& grid);

// Whether a B-spline stencil of a node within the sphere can reach the slab's planes: a node at
// grid coordinate u = x K / L spreads to planes floor(u) - p + 1 .. floor(u) (modulo K).
bool reaches_slab(const CellSphere& sphere, const SlabPlanes& slab, const PeriodicBox& box);

// The halo of the cells `owned` (of spheres.size() cells, stacked in owner order): the other
// cells whose spheres come within `reach` (the largest of the real-space cutoffs and the near
// distances plus h) of an owned cell's in the box, or that reach one of `slabs` (the rank's planes
// of each grid its products use); ascending. Free space (no box) or no slabs: every cell not
// owned.
std::vector<int> cell_halo(const std::vector<CellSphere>& spheres, OwnedRange owned, const std::optional<PeriodicBox>& box,
                           double reach, const std::vector<SlabPlanes>& slabs);

// What a rank's halo in a step's cell layers (cell_layers.h) is taken from: the reach about its
// owned cells, its slabs of the grids split over the ranks, and whether its part reaches every
// node (free space, or a grid every rank holds whole).
struct HaloExtent {
  double reach = 0.0;
  std::vector<SlabPlanes> slabs;
  bool every_cell = false;
};
// The extent of the layers' products on these grids (null: none; a null single-layer grid is
// free space), `near_reach` the owned cells' largest near distance plus mesh size.
HaloExtent layers_halo_extent(double near_reach, const SpmeGrid* single_grid, const SpmeGrid* double_grid);
// The halo of the layers' products and of other operators whose grids' slabs of this rank are
// `other_slabs`: cell_halo over both slabs, or every cell not owned.
std::vector<int> cell_halo(const std::vector<CellSphere>& spheres, OwnedRange owned, const std::optional<PeriodicBox>& box,
                           const HaloExtent& extent, const std::vector<SlabPlanes>& other_slabs);

}  // namespace rbcflow
