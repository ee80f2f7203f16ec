#include "cell_owners.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "libsolver/parallel/ownership.h"

namespace rbcflow {

bool CellOwners::in_cell_order() const {
  for (std::size_t k = 0; k < order.size(); ++k)
    if (order[k] != static_cast<int>(k)) return false;
  return true;
}

Eigen::MatrixXd CellOwners::to_owner_order(const Eigen::MatrixXd& stacked, int nodes_per_cell) const {
  Eigen::MatrixXd out(stacked.rows(), stacked.cols());
  for (std::size_t k = 0; k < order.size(); ++k)
    out.middleRows(static_cast<Eigen::Index>(k) * nodes_per_cell, nodes_per_cell) =
        stacked.middleRows(static_cast<Eigen::Index>(order[k]) * nodes_per_cell, nodes_per_cell);
  return out;
}

Eigen::MatrixXd CellOwners::to_cell_order(const Eigen::MatrixXd& stacked, int nodes_per_cell) const {
  Eigen::MatrixXd out(stacked.rows(), stacked.cols());
  for (std::size_t k = 0; k < order.size(); ++k)
    out.middleRows(static_cast<Eigen::Index>(order[k]) * nodes_per_cell, nodes_per_cell) =
        stacked.middleRows(static_cast<Eigen::Index>(k) * nodes_per_cell, nodes_per_cell);
  return out;
}

CellOwners owners_by_block(int cells, int ranks) {
  CellOwners o;
  o.order.resize(static_cast<std::size_t>(cells));
  std::iota(o.order.begin(), o.order.end(), 0);
  for (int r = 0; r < ranks; ++r) o.first.push_back(owned_block(cells, r, ranks).begin);
  o.first.push_back(cells);
  return o;
}

CellOwners owners_by_slab(const std::vector<double>& coordinate, const std::vector<double>& slab_start, double length) {
  const std::size_t p = slab_start.size();
  bool valid = p > 0 && slab_start.front() == 0.0 && length > 0 && std::isfinite(length);
  for (std::size_t r = 1; valid && r < p; ++r) valid = slab_start[r - 1] <= slab_start[r] && slab_start[r] <= length;
  if (!valid) throw std::invalid_argument("owners_by_slab: slab starts must rise from 0 within the length, one a rank");
  std::vector<int> owner(coordinate.size());
  for (std::size_t c = 0; c < coordinate.size(); ++c) {
    if (!std::isfinite(coordinate[c])) throw std::invalid_argument("owners_by_slab: a cell's coordinate is not finite");
    double x = std::fmod(coordinate[c], length);
    if (x < 0) x += length;
    if (x >= length) x = 0;  // -tiny % length + length rounds to length
    owner[c] = static_cast<int>(std::upper_bound(slab_start.begin(), slab_start.end(), x) - slab_start.begin()) - 1;
  }
  CellOwners o;
  o.order.resize(coordinate.size());
  std::iota(o.order.begin(), o.order.end(), 0);
  std::stable_sort(o.order.begin(), o.order.end(), [&](int a, int b) { return owner[a] < owner[b]; });
  o.first.assign(p + 1, 0);
  for (int r : owner) ++o.first[static_cast<std::size_t>(r) + 1];
  std::partial_sum(o.first.begin(), o.first.end(), o.first.begin());
  return o;
}

CellOwners cell_owners(const std::vector<SHCoeffs>& cells, const CellGrids& grids, const LayerDomain& domain,
                       bool with_double_layer, SpmeGridCache* grid_cache) {
  const int nc = static_cast<int>(cells.size()), p = domain.ranks.size();
  if (p == 1 || !domain.box || nc == 0) return owners_by_block(nc, p);
  const long nodes = static_cast<long>(nc) * grids.n_grid->grid().size();
  const std::shared_ptr<const SpmeGrid> grid = cell_layer_grid(domain, nodes, with_double_layer, grid_cache);
  if (!grid->distributed()) return owners_by_block(nc, p);
  // Every rank's first plane, from each rank's own (a sum of vectors zero but at the rank's
  // entry); a rank without planes (the last ones, when the ranks outnumber them) starts at the end.
  const int axis = grid->axis(0);
  const double length = domain.box->length(axis);
  Eigen::VectorXd start = Eigen::VectorXd::Zero(p);
  start[domain.ranks.rank()] = grid->planes() > 0 ? grid->first_plane() * (length / grid->size(0)) : length;
  domain.ranks.sum(start);
  std::vector<double> coordinate(static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) coordinate[static_cast<std::size_t>(c)] = grids.n_grid->synthesize(cells[c]).col(axis).mean();
  return owners_by_slab(coordinate, std::vector<double>(start.data(), start.data() + p), length);
}

}  // namespace rbcflow
