#pragma once
// The step's traction f^n on the ranks: the single-layer density of (10) and (12). Each rank
// computes the membranes of the cells it owns in the step's products (cell_owners.h) and holds
// their rows; the step's operators read those and the rows of their halo, which each names
// once it has found it (DensityHalo, cell_layers.h): only the halo's rows travel, not every
// cell's to every rank. On one rank every row is here.
#include <Eigen/Core>
#include <vector>

#include "libsolver/operators/cell_layers.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/owned_rows.h"

namespace rbcflow {

class StepTraction {
 public:
  // `owned`: the rows of this rank's cells in `owners`' order (positions owners.first[rank] ..
  // owners.first[rank + 1] - 1).
  StepTraction(Eigen::MatrixXd owned, CellOwners owners, int nodes_per_cell, const Communicator& ranks);

  // Stacked in owner order: the owned cells' rows and those brought so far, zero elsewhere. The
  // operators refer to this matrix; it stays in place until release().
  const Eigen::MatrixXd& density() const { return density_; }
  // Brings the rows of the cells of `halo` (positions in owner order) that are not here yet.
  // Collective.
  void bring(const std::vector<int>& halo);
  DensityHalo bringer() {
    return [this](const std::vector<int>& halo) { bring(halo); };
  }
  long rows_received() const { return homes_.rows_received(); }
  // The density in cell order (the rows never brought zero); the operators are done with it.
  Eigen::MatrixXd release();

 private:
  CellOwners owners_;
  int nodes_per_cell_ = 0;
  Communicator ranks_;
  OwnedRows homes_;          // the rows in owner order, each rank's owned cells'
  Eigen::MatrixXd owned_;    // this rank's rows of homes_
  std::vector<bool> here_;   // by position in owner order: its rows are in density_
  Eigen::MatrixXd density_;
};

}  // namespace rbcflow
