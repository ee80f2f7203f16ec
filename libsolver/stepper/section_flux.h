#pragma once
// The volume flux through the branches of a vessel (geometry/vessel/vessel_branch.h) for the flow of one step: the velocity at the section's
// quadrature points from the boundary integral representation,
//   R(x) = <u> - (1/(8 pi mu)) N_W F - (1/(8 pi mu)) N_D f + (1 - lambda)/(8 pi) K_D U,
// which is u(x) in the plasma and lambda u(x) inside a cell (Pozrikidis 1992, eq. 5.3.8), the
// cells' layers with their nearly-singular corrections (cell_layers_at_points.h); a point is
// inside a cell by the winding number of the cell's grid triangulation. The wall's operator at
// the points is built once (the wall and the sections do not move). On several ranks each rank
// measures the clearance of its own cells and tests the points against them; the least
// clearance and the points inside are then the ranks' (exact: the same as on one rank).
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "geometry/surface/sh_surface.h"
#include "geometry/vessel/vessel_branch.h"
#include "libsolver/operators/cell_layers.h"
#include "libsolver/stepper/wall_coupling.h"

namespace rbcflow {

// The cells of a step, for section_fluxes: their layers, traction f and surface velocity U
// stacked over the cells, the shapes of this rank's own cells in the layers (layers->owned(),
// in that order: every cell on one rank) and the grid the densities live on.
struct CellsAtStep {
  const CellLayers* layers = nullptr;
  const Eigen::MatrixXd* traction = nullptr;
  const Eigen::MatrixXd* velocity = nullptr;
  const std::vector<SHSurface>* own_shapes = nullptr;
  const SHTransform* grid = nullptr;
  double viscosity_ratio = 1.0;
  // Brings the rows of the traction and the velocity the sections' operator reads
  // (CellLayersAtPoints's halo; halo_density.h).
  DensityHalo bring_densities;
};

// One flux per branch, each measured through one of the branch's candidate sections (all
// cross-sections of one straight piece of vessel, so each carries the branch's flux at every
// instant: the fluid is incompressible and the wall rigid): the one farthest from every cell's
// grid points, where the velocity is smooth over the section and its quadrature converges
// fast (through a cell the velocity gradient jumps at the membrane: a 8 x 24 section 0.1 from a
// red cell's middle is 0.5% off).
class SectionFluxMeter {
 public:
  // `wall` must outlive the meter; each branch needs at least one section.
  SectionFluxMeter(const WallCoupling& wall, std::vector<std::vector<SectionQuadrature>> branches);

  int num_branches() const { return static_cast<int>(branches_.size()); }
  // The flux through each branch, along its sections' normal; `cells` null without cells.
  std::vector<double> fluxes(const Eigen::Vector3d& mean_velocity, const PointField& wall_force,
                             const CellsAtStep* cells);
  // The points fluxes() evaluates the cells' layers at, one section of each branch: known before
  // the sections are chosen where each branch's candidates have as many points; else none.
  std::optional<long> points_per_step() const;
  // This rank's slabs of the grids the last fluxes() with cells read the cells' densities on
  // (CellLayersAtPoints::slabs; empty before): part of the step's halo (CellLayers::halo_with).
  const std::vector<SlabPlanes>& slabs() const { return slabs_; }

 private:
  struct Candidate {
    SectionQuadrature section;
    PointField points;  // wrapped into the box
    WallOperator wall_at_points;
  };
  // The candidate of branch b farthest from the nodes of the cells of `layers` (null: none).
  int clearest(int b, const CellLayers* layers) const;

  PeriodicBox box_;
  std::vector<std::vector<Candidate>> branches_;
  std::vector<SlabPlanes> slabs_;
};

}  // namespace rbcflow
