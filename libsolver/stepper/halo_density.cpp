#include "halo_density.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace rbcflow {

HaloDensity::HaloDensity(Eigen::MatrixXd owned, CellOwners owners, int nodes_per_cell, const Communicator& ranks,
                         std::vector<int> held)
    : owners_(std::move(owners)),
      nodes_per_cell_(nodes_per_cell),
      ranks_(ranks),
      held_(std::move(held)),
      homes_(owners_.first, nodes_per_cell, ranks),
      owned_(std::move(owned)) {
  const int nc = static_cast<int>(owners_.order.size());
  const int np = nodes_per_cell_;
  const int first = owners_.first[ranks.rank()], end = owners_.first[ranks.rank() + 1];
  if (owned_.rows() != static_cast<Eigen::Index>(end - first) * np || owned_.cols() != 3)
    throw std::invalid_argument("HaloDensity: the owned rows do not fit this rank's cells");
  homes_.hold(held_);  // checks that the owned cells are held
  here_.assign(static_cast<std::size_t>(nc), false);
  std::fill(here_.begin() + first, here_.begin() + end, true);
  density_ = Eigen::MatrixXd::Zero(homes_.held_rows(), 3);
  if (first < end) density_.middleRows(held_row(first), owned_.rows()) = owned_;
}

Eigen::Index HaloDensity::held_row(int k) const {
  const auto at = std::lower_bound(held_.begin(), held_.end(), k);
  if (at == held_.end() || *at != k) throw std::logic_error("HaloDensity: a cell read is not among the held cells");
  return static_cast<Eigen::Index>(at - held_.begin()) * nodes_per_cell_;
}

void HaloDensity::bring(const std::vector<int>& halo) {
  if (ranks_.size() == 1) return;  // every row is here
  const int np = nodes_per_cell_;
  std::vector<int> wanted, rows;  // positions in owner order (halo is ascending), their node rows
  for (const int k : halo) {
    if (here_[static_cast<std::size_t>(k)]) continue;
    held_row(k);  // held, or a logic error before any rank exchanges
    here_[static_cast<std::size_t>(k)] = true;
    wanted.push_back(k);
    for (int i = 0; i < np; ++i) rows.push_back(k * np + i);
  }
  homes_.read_only(rows);
  const Eigen::MatrixXd brought = homes_.gather_read_held(owned_);
  for (const int k : wanted) density_.middleRows(held_row(k), np) = brought.middleRows(held_row(k), np);
}

Eigen::MatrixXd HaloDensity::release() {
  if (ranks_.size() > 1) return std::move(owned_);
  if (owners_.in_cell_order()) return std::move(density_);
  return owners_.to_cell_order(density_, nodes_per_cell_);
}

}  // namespace rbcflow
