#pragma once
// Random placement of copies of a reference cell in a periodic box, optionally inside a vessel
// wall, without overlap (periodic images included): random sequential addition at full size,
// and where that jams before the count, shrink-then-grow compression (all cells placed at a
// reduced size, then alternately moved at random and grown, a Monte Carlo compression of hard
// bodies; the moves keep every state free of overlap; the wall and a cell's own periodic images
// are tested at full size throughout, so no cell waits where it cannot grow). A growth that
// makes a few cells touch moves just those apart (random moves that clear everything) instead
// of being refused, so the sweeps do not grow with the count and placement costs O(count):
// bench_collision's BM_PlaceWideTubeCells. Deterministic for a seed on every
// machine: doubles come from the raw 64-bit output of std::mt19937_64.
//
// Overlap and wall tests use the reference surface's grid triangulation at `check_order`:
// every vertex of one cell at least `gap` from the other's triangles and outside it, every
// vertex at least `gap` inside the wall.
//
// Tubes narrower than the cell (not even one undeformed cell fits) get the cells stacked along
// the axis at equal spacing, each deformed in advance: stretched edge-on by a volume-preserving
// stretch that keeps the faces' area (the default; see PlacedCell), or folded face-on into a
// parachute that keeps the cell's area and volume. The membrane's rest shape stays the undeformed cell, so the fold or
// stretch is an initial deformation that the flow relaxes into the tube's parachutes.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "geometry/surface/sh_surface.h"
#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

enum class CellOrientation {
  random,      // uniform over rotations
  along_axis,  // symmetry axis (the reference's z) along the vessel axis, random spin about it
  automatic,   // along_axis in narrow tubes (below kNarrowTubeRatio cell diameters), else random
};

// The paper's narrow tubes hold cells as coins in a stack (section 11.2, fig. 12). A tube
// whose equivalent diameter 2 sqrt(V / (pi L)) is below this many cell diameters (twice the
// bounding radius: 2.75 for the red cell; 3.6 = 1.3 x 2.75 covers the paper's D = 3.5) lets a
// turned cell fit only near the axis, and random orientations jam before H_T = 0.30 (6 cells
// in a D = 3.5 tube of length 8 stop at 99% of full size). Below one cell diameter an undeformed cell does not
// fit at all (the paper's D = 1.75..2.5 tubes hold parachutes, not discs): the cells are
// placed pre-deformed.
inline constexpr double kNarrowTubeRatio = 1.3;

// How cells start in tubes narrower than the cell (stack_stretched, stack_parachutes in
// cell_placement.cpp).
enum class NarrowStart {
  stretched,  // edge-on, the plane of the disc along the axis, stretched along it and squeezed across
  parachute,  // face-on, folded into a parachute of the lumen's radius (geometry/surface/parachute_fold.h)
};

struct PlacementSpec {
  Eigen::Vector3d box = Eigen::Vector3d::Zero();  // periodic box sides
  int count = 0;
  double gap = 0.0;  // smallest cell-cell and cell-wall distance
  std::uint64_t seed = 1;
  CellOrientation orientation = CellOrientation::automatic;
  int check_order = 10;  // order of the triangulation used by the tests
  NarrowStart narrow_start = NarrowStart::stretched;
  // The mean flow: parachutes point their nose along it (along the tube axis where it is zero).
  Eigen::Vector3d flow = Eigen::Vector3d::Zero();
};

struct PlacedCell {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();     // where the reference's centroid goes
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // rest shape x = R (x_ref - centroid) + position
  // The initial shape is x = S R (x_ref - centroid) + position: S symmetric with det S = 1
  // (the volume kept), the identity except for cells placed pre-deformed in narrow tubes.
  Eigen::Matrix3d stretch = Eigen::Matrix3d::Identity();
};

struct Placement {
  std::vector<PlacedCell> cells;
  // Tube hematocrit count * cell volume / lumen volume (the box volume without a vessel).
  double hematocrit = 0.0;
  int compression_sweeps = 0;  // 0 when random sequential addition reached the count
  // Cells placed pre-deformed (narrow tubes): the stretch factors of the cell along the tube
  // axis, across it in the cell's plane and through its thickness (product 1); else all 1.
  Eigen::Vector3d stretch_factors = Eigen::Vector3d::Ones();
  // Cells folded into parachutes (narrow tubes, NarrowStart::parachute): the folded reference,
  // centroid at the origin, nose along z; each cell's initial shape is it turned by the cell's
  // rotation. Its outer radius and length are given.
  std::optional<SHSurface> parachute;
  double parachute_radius = 0, parachute_length = 0;
};

// Throws std::invalid_argument for a bad spec, std::runtime_error (saying how many cells fitted
// and the hematocrit reached) when the count cannot be placed. `vessel` may be null.
Placement place_cells(const SHSurface& reference, const PlacementSpec& spec, const VesselMesh* vessel);

// The placed copies of `reference`: their rest shapes (the membranes' reference) and their
// initial shapes (the rest shapes stretched by PlacedCell::stretch about their centroids, or the
// placement's parachute turned and moved as the rest shape).
std::vector<SHSurface> placed_surfaces(const SHSurface& reference, const std::vector<PlacedCell>& cells);
std::vector<SHSurface> initial_surfaces(const SHSurface& reference, const Placement& placement);

}  // namespace rbcflow
