#include "libsolver/stepper/cell_centroids.h"

#include <span>
#include <stdexcept>

#include "geometry/surface/sh_surface.h"
#include "libsolver/parallel/share_blocks.h"

namespace rbcflow {

std::vector<Eigen::Vector3d> volume_centroids(const std::vector<Cell>& cells, const SHTransform& transform,
                                              const CellOwners& holders, const Communicator& ranks) {
  if (holders.order.size() != cells.size()) throw std::invalid_argument("volume_centroids: not one holder a cell");
  std::vector<Eigen::Vector3d> x(cells.size(), Eigen::Vector3d::Zero());
  const int first = holders.first[ranks.rank()], end = holders.first[ranks.rank() + 1];
#pragma omp parallel for schedule(dynamic)
  for (int k = first; k < end; ++k) {
    const auto c = static_cast<std::size_t>(holders.order[k]);
    x[c] = volume_centroid(cells[c].shape.geometry(transform));
  }
  std::vector<std::vector<std::span<double>>> items;  // in the holders' order: their blocks are share_blocks'
  for (const int c : holders.order) items.push_back({std::span<double>(x[static_cast<std::size_t>(c)].data(), 3)});
  share_blocks(ranks, items);
  return x;
}

}  // namespace rbcflow
