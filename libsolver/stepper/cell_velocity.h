#pragma once
// The cell-surface velocity of eq. (6) (step (i), eq. 10, without walls):
//   u - (1 - lambda)/(4 pi (1 + lambda)) K u = -1/(4 pi mu (1 + lambda)) N f + 2/(1 + lambda) u_b
// with f the hydrodynamic traction (membrane traction of eq. 23 minus any body-force density)
// and u_b the background: the mean velocity <u> in a periodic box, the imposed flow in free
// space. lambda = 1 needs no solve; otherwise GMRES (well conditioned for any lambda).
#include <Eigen/Core>

#include "libsolver/operators/cell_layers.h"
#include "libsolver/linear/preconditioned_gmres.h"

namespace rbcflow {

struct VelocitySolve {
  // This rank's cells' rows (the layers' owned(), in their order), stacked nodes x 3: every
  // node on one rank. Not gathered: the caller brings the rows it needs (halo_density.h).
  Eigen::MatrixXd velocity;
  GmresReport gmres;         // iterations 0 for lambda = 1
  long rows_received = 0;    // node rows this rank received from the others in the solve's products
};

// mu = 1 (lengths, times and viscosity in the paper's units). `traction`: at the layers' held
// rows (CellLayers::nodes(); every cell's where every cell is held), the layers' own
// single-layer density where they were built for one. background: every node's rows, the same
// on every rank, or this rank's cells' (as the returned velocity). `initial_guess`: every node's
// rows or this rank's cells'. `image` (optional): on entry, when it has the guess's shape, the
// left-hand side of (6) for `initial_guess`, which saves the solve's first product; on return,
// the left-hand side for the returned velocity, this rank's cells' rows
// (preconditioned_gmres.h: no product). `background_part` (optional, at the held rows): this
// rank's part of a further background that is the sum of the ranks' parts (the wall's velocity
// at the cells, wall/wall_operator.h's TargetRows), zero outside the held cells; on several
// ranks each receives only its rows of the right-hand side, summed from the ranks' parts of it
// (parallel/owned_rows.h), never the whole.
VelocitySolve solve_cell_velocity(CellLayers& layers, const Eigen::MatrixXd& traction, double viscosity_ratio,
                                  const Eigen::MatrixXd& background, double tolerance, int max_iterations,
                                  const Eigen::MatrixXd& initial_guess = {}, Eigen::MatrixXd* image = nullptr,
                                  const Eigen::MatrixXd* background_part = nullptr);

}  // namespace rbcflow
