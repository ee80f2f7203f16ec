#include "cell_owners.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <span>
#include <stdexcept>

#include "libsolver/parallel/ownership.h"
#include "libsolver/parallel/share_blocks.h"

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

CellOwners owners_along(const std::vector<double>& coordinate, double length, int ranks) {
  if (!(length > 0) || !std::isfinite(length) || ranks < 1) throw std::invalid_argument("owners_along: bad length or ranks");
  const int n = static_cast<int>(coordinate.size());
  std::vector<double> x(coordinate.size());
  for (std::size_t c = 0; c < coordinate.size(); ++c) {
    if (!std::isfinite(coordinate[c])) throw std::invalid_argument("owners_along: a cell's coordinate is not finite");
    x[c] = std::fmod(coordinate[c], length);
    if (x[c] < 0) x[c] += length;
    if (x[c] >= length) x[c] = 0;  // -tiny % length + length rounds to length
  }
  std::vector<int> along(coordinate.size());
  std::iota(along.begin(), along.end(), 0);
  std::stable_sort(along.begin(), along.end(), [&](int a, int b) { return x[a] < x[b]; });
  CellOwners o = owners_by_block(n, ranks);
  for (int r = 0; r < ranks; ++r) {  // rank r's cells, by index
    std::vector<int> mine(along.begin() + o.first[r], along.begin() + o.first[r + 1]);
    std::sort(mine.begin(), mine.end());
    std::copy(mine.begin(), mine.end(), o.order.begin() + o.first[r]);
  }
  return o;
}

CellOwners cell_owners(const std::vector<CellSphere>& spheres, long nodes_per_cell, const LayerDomain& domain,
                       bool with_double_layer, SpmeGridCache* grid_cache) {
  const int nc = static_cast<int>(spheres.size()), p = domain.ranks.size();
  if (p == 1 || !domain.box || nc == 0) return owners_by_block(nc, p);
  const std::shared_ptr<const SpmeGrid> grid = cell_layer_grid(domain, nc * nodes_per_cell, with_double_layer, grid_cache);
  if (!grid->distributed()) return owners_by_block(nc, p);
  const int axis = grid->axis(0);
  std::vector<double> coordinate(static_cast<std::size_t>(nc));
  for (int c = 0; c < nc; ++c) coordinate[static_cast<std::size_t>(c)] = spheres[static_cast<std::size_t>(c)].center[axis];
  return owners_along(coordinate, domain.box->length(axis), p);
}

void share_spheres(std::vector<CellSphere>& spheres, const CellOwners& holders, const Communicator& ranks) {
  if (holders.order.size() != spheres.size()) throw std::invalid_argument("share_spheres: not one sphere a cell");
  std::vector<std::vector<std::span<double>>> items;  // in the holders' order: their blocks are share_blocks'
  for (const int c : holders.order) {
    CellSphere& s = spheres[static_cast<std::size_t>(c)];
    items.push_back({std::span<double>(s.center.data(), 3), std::span<double>(&s.radius, 1), std::span<double>(&s.area, 1)});
  }
  share_blocks(ranks, items);
}

}  // namespace rbcflow
