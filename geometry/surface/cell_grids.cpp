#include "geometry/surface/cell_grids.h"

#include <stdexcept>
#include <string>

namespace rbcflow {

std::shared_ptr<const CellGrids> CellGrids::make(int order, int dealias_order) {
  if (order < 2 || dealias_order < order) {
    throw std::invalid_argument("CellGrids: need 2 <= N <= M, got N = " + std::to_string(order) +
                                ", M = " + std::to_string(dealias_order));
  }
  auto g = std::make_shared<CellGrids>();
  g->order = order;
  g->dealias_order = dealias_order;
  g->n_grid = std::make_shared<const SHTransform>(order, SphGrid::gauss(order), 2);
  g->m_grid = dealias_order == order
                  ? g->n_grid
                  : std::make_shared<const SHTransform>(dealias_order, SphGrid::gauss(dealias_order), 2);
  return g;
}

}  // namespace rbcflow
