#pragma once
// The step's traction f^n on the ranks: the single-layer density of (10) and (12). Each rank
// computes the membranes of its block of the cells by index (owned_block) and holds their rows;
// the step's operators read the rows of the cells they own in the products (cell_owners.h) and
// of their halo, which each names once it has found it (DensityHalo, cell_layers.h): only those
// rows travel, not every cell's to every rank. On one rank every row is here.
#include <Eigen/Core>
#include <vector>

#include "libsolver/operators/cell_layers.h"
#include "libsolver/operators/cell_owners.h"
#include "libsolver/parallel/owned_rows.h"

namespace rbcflow {

class StepTraction {
 public:
  // `block`: the rows of this rank's block of the cells (owned_block), in cell order;
  // `owners`: the order of the step's products.
  StepTraction(Eigen::MatrixXd block, CellOwners owners, int nodes_per_cell, const Communicator& ranks);

  // Stacked in owner order: the block's rows and those brought so far, zero elsewhere. The
  // operators refer to this matrix; it stays in place until release().
  const Eigen::MatrixXd& density() const { return density_; }
  // Brings the rows of this rank's owned cells in the products and of `halo` (positions in owner
  // order) that are not here yet. Collective.
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
  OwnedRows homes_;            // the rows by owned_block, where they are computed
  Eigen::MatrixXd block_;      // this rank's rows of homes_
  std::vector<int> position_;  // by cell: its position in owner order
  std::vector<bool> here_;     // by cell: its rows are in density_
  Eigen::MatrixXd density_;
};

}  // namespace rbcflow
