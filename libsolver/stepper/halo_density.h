#pragma once
// A density of the step on the ranks, held by the cells' owners in the step's products
// (cell_owners.h): the traction f^n, the single-layer density of (10) and (12), and the
// velocity U^n, the double-layer density of the flux sections' velocity. Each rank holds its
// owned cells' rows, with room for those of the cells its layers hold (the step's halo); an
// operator reads the owned rows and those of its halo, which it names once it has found it
// (DensityHalo, cell_layers.h): only the halo's rows travel, not every cell's to every rank,
// and no rank holds a row of every cell. On one rank every row is here.
#include <Eigen/Core>
#include <vector>

#include "libsolver/operators/cell_layers.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/owned_rows.h"

namespace rbcflow {

class HaloDensity {
 public:
  // `owned`: the rows of this rank's cells in `owners`' order (positions owners.first[rank] ..
  // owners.first[rank + 1] - 1). `held`: the cells whose rows the density has room for
  // (positions in owner order, ascending, the owned among them: the step's layers' held_cells();
  // one process: every cell). A rank may hold none.
  HaloDensity(Eigen::MatrixXd owned, CellOwners owners, int nodes_per_cell, const Communicator& ranks,
              std::vector<int> held);

  // At the held cells' rows (the layers' held layout, CellLayers::nodes()): the owned cells'
  // rows and those brought so far, zero at the others. The operators refer to this matrix; it
  // stays in place until release().
  const Eigen::MatrixXd& density() const { return density_; }
  // Brings the rows of the cells of `halo` (positions in owner order, held) that are not here
  // yet. Collective.
  void bring(const std::vector<int>& halo);
  DensityHalo bringer() {
    return [this](const std::vector<int>& halo) { bring(halo); };
  }
  // This rank's owned cells' rows, in owner order (as given).
  const Eigen::MatrixXd& owned() const { return owned_; }
  long rows_received() const { return homes_.rows_received(); }
  // The operators are done with the density. One rank: every cell's rows in cell order; several:
  // this rank's owned cells' rows in owner order (CellStepper::cells_for_output brings them).
  Eigen::MatrixXd release();

 private:
  Eigen::Index held_row(int k) const;  // the first row of held cell k (position in owner order) in density_
  CellOwners owners_;
  int nodes_per_cell_ = 0;
  Communicator ranks_;
  std::vector<int> held_;    // positions in owner order
  OwnedRows homes_;          // the rows in owner order, each rank's owned cells', held as held_
  Eigen::MatrixXd owned_;    // this rank's rows of homes_
  std::vector<bool> here_;   // by position in owner order: its rows are in density_
  Eigen::MatrixXd density_;
};

}  // namespace rbcflow
