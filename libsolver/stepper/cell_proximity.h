#pragma once
// Which cells come close to which, and how far a point is from a cell's spectral surface: the
// geometry shared by the kinematic collision removal (collision.h) and the contact repulsion
// (contact_force.h). Candidates come from bounding spheres and bins of the cells' centres;
// distances from the surface itself (Gauss-Newton projection, surface_projection.h, seeded by
// an AABB tree over the grid triangulation), not from the triangulation, whose chord sag at
// N = 16 is of the order of the collision threshold.
#include <Eigen/Core>
#include <memory>
#include <optional>
#include <vector>

#include "geometry/cgal/aabb_tree.h"
#include "geometry/sph/sph_grid.h"
#include "geometry/sph/sph_transform.h"
#include "geometry/surface/surface_projection.h"

namespace rbcflow {

// One cell as the proximity queries see it: its grid points, a bounding sphere about their
// mean, and (once build_tree is called) the AABB tree over its grid triangulation.
struct CellView {
  Eigen::MatrixXd points;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
  TriangleMesh mesh;
  std::unique_ptr<TriangleAabbTree> tree;
};

// The points of `coeffs` on the grid of `t` and their bounding sphere (no tree).
CellView cell_view(const SHCoeffs& coeffs, const SHTransform& t);
// Adds the triangulation of `coeffs` on the grid of `t` and its AABB tree to `view`.
void build_tree(CellView& view, const SHCoeffs& coeffs, const SHTransform& t);

// Cell b's image at b + offset is near cell a; `pair` numbers the unordered pair (a, b, +-offset).
struct Neighbour {
  int b = 0;
  Eigen::Vector3d offset;
  int pair = 0;
};

// Every cell's images whose bounding spheres come within `margin` of its own.
struct Neighbourhood {
  std::vector<std::vector<Neighbour>> near;  // by cell
  int pairs = 0;
};

// Each close pair is listed from both sides (a cell's own periodic images included, once), in
// ascending order of the cells. `period`: box sides of the periodic directions, 0 where not
// periodic. Views with radius 0 and no points (cells not held here) must not be passed.
Neighbourhood find_neighbours(const std::vector<CellView>& views, const Eigen::Vector3d& period, double margin);

// The projection of q (in b's own frame: a point of cell a minus the neighbour's offset) onto
// cell b's spectral surface when q may be within `reach` of it (inside counts as within), else
// nothing. `b` needs its tree; `grid` is the grid of b's view.
std::optional<SurfaceProjection> project_within(const CellView& b, const SHCoeffs& b_coeffs, const SphGrid& grid,
                                                const Eigen::Vector3d& q, double reach);

}  // namespace rbcflow
