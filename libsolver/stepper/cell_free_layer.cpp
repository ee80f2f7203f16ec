#include "cell_free_layer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rbcflow {

double cell_free_layer(const std::vector<SHSurface>& cells, const SHTransform& grid, const TubeSection& tube,
                       double period, const CellFreeLayerBins& bins, const Communicator& ranks) {
  if (ranks.sum(static_cast<long>(cells.size())) == 0) throw std::invalid_argument("cell_free_layer: no cells");
  if (!(bins.slice_length > 0) || bins.sectors < 1 || !(period > 0))
    throw std::invalid_argument("cell_free_layer: the bins and the period must be positive");
  const int a = tube.axis, u = (a + 1) % 3, v = (a + 2) % 3;
  const int slices = std::max(1, static_cast<int>(std::lround(period / bins.slice_length)));
  std::vector<double> edge(static_cast<std::size_t>(slices) * bins.sectors, -1.0);
  for (const SHSurface& cell : cells) {
    const Eigen::MatrixXd x = grid.synthesize(cell.coeffs());
    for (Eigen::Index p = 0; p < x.rows(); ++p) {
      const double du = x(p, u) - tube.axis_point[u], dv = x(p, v) - tube.axis_point[v];
      const double along = x(p, a) - tube.axis_point[a];
      const double s = along / period - std::floor(along / period);  // in [0, 1]: cells are not wrapped
      const int slice = std::min(slices - 1, static_cast<int>(s * slices));
      const double angle = std::atan2(dv, du) / (2 * std::numbers::pi) + 0.5;
      const int sector = std::min(bins.sectors - 1, static_cast<int>(angle * bins.sectors));
      double& e = edge[static_cast<std::size_t>(slice) * bins.sectors + sector];
      e = std::max(e, std::hypot(du, dv));
    }
  }
  ranks.max(edge);
  double sum = 0.0;
  int held = 0;
  for (const double e : edge) {
    if (e < 0) continue;
    sum += tube.radius - e;
    ++held;
  }
  return sum / held;
}

}  // namespace rbcflow
