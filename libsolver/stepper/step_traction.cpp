#include "step_traction.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace rbcflow {

StepTraction::StepTraction(Eigen::MatrixXd block, CellOwners owners, int nodes_per_cell, const Communicator& ranks)
    : owners_(std::move(owners)),
      nodes_per_cell_(nodes_per_cell),
      ranks_(ranks),
      homes_(static_cast<int>(owners_.order.size()), nodes_per_cell, ranks),
      block_(std::move(block)) {
  const int nc = static_cast<int>(owners_.order.size());
  const int np = nodes_per_cell_;
  position_.resize(static_cast<std::size_t>(nc));
  for (int k = 0; k < nc; ++k) position_[static_cast<std::size_t>(owners_.order[k])] = k;
  here_.assign(static_cast<std::size_t>(nc), false);
  density_ = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(nc) * np, 3);
  const OwnedRange mine = owned_block(nc, ranks);
  if (block_.rows() != static_cast<Eigen::Index>(mine.size()) * np || block_.cols() != 3)
    throw std::invalid_argument("StepTraction: the block's rows do not fit this rank's cells");
  for (int c = mine.begin; c < mine.end; ++c) {
    density_.middleRows(static_cast<Eigen::Index>(position_[c]) * np, np) = block_.middleRows((c - mine.begin) * np, np);
    here_[static_cast<std::size_t>(c)] = true;
  }
}

void StepTraction::bring(const std::vector<int>& halo) {
  if (ranks_.size() == 1) return;  // every row is here
  const int np = nodes_per_cell_;
  std::vector<int> wanted;  // cells by index
  auto want = [&](int k) {
    const int c = owners_.order[static_cast<std::size_t>(k)];
    if (here_[static_cast<std::size_t>(c)]) return;
    here_[static_cast<std::size_t>(c)] = true;
    wanted.push_back(c);
  };
  const int r = ranks_.rank();
  for (int k = owners_.first[r]; k < owners_.first[r + 1]; ++k) want(k);
  for (const int k : halo) want(k);
  std::sort(wanted.begin(), wanted.end());
  std::vector<int> rows;
  rows.reserve(wanted.size() * static_cast<std::size_t>(np));
  for (const int c : wanted)
    for (int i = 0; i < np; ++i) rows.push_back(c * np + i);
  homes_.read_only(rows);
  const Eigen::MatrixXd brought = homes_.gather_read(block_);  // cell order
  for (const int c : wanted)
    density_.middleRows(static_cast<Eigen::Index>(position_[c]) * np, np) = brought.middleRows(static_cast<Eigen::Index>(c) * np, np);
}

Eigen::MatrixXd StepTraction::release() {
  if (owners_.in_cell_order()) return std::move(density_);
  return owners_.to_cell_order(density_, nodes_per_cell_);
}

}  // namespace rbcflow
