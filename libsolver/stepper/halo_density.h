#pragma once
// A density of the step on the ranks, held by the cells' owners in the step's products
// (cell_owners.h): the traction f^n, the single-layer density of (10) and (12), and the
// velocity U^n, the double-layer density of the flux sections' velocity. Each rank holds its
// owned cells' rows; an operator reads those and the rows of its halo, which it names once it
// has found it (DensityHalo, cell_layers.h): only the halo's rows travel, not every cell's to
// every rank. On one rank every row is here.
#include <Eigen/Core>
#include <vector>

#include "libsolver/operators/cell_layers.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/owned_rows.h"

namespace rbcflow {

class HaloDensity {
 public:
  // `owned`: the rows of this rank's cells in `owners`' order (positions owners.first[rank] ..
  // owners.first[rank + 1] - 1).
  HaloDensity(Eigen::MatrixXd owned, CellOwners owners, int nodes_per_cell, const Communicator& ranks);

  // Stacked in owner order: the owned cells' rows and those brought so far, zero elsewhere. The
  // operators refer to this matrix; it stays in place until release().
  const Eigen::MatrixXd& density() const { return density_; }
  // Brings the rows of the cells of `halo` (positions in owner order) that are not here yet.
  // Collective.
  void bring(const std::vector<int>& halo);
  DensityHalo bringer() {
    return [this](const std::vector<int>& halo) { bring(halo); };
  }
  // This rank's owned cells' rows, in owner order (as given).
  const Eigen::MatrixXd& owned() const { return owned_; }
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
