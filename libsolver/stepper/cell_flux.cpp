#include "cell_flux.h"

#include <stdexcept>

namespace rbcflow {

double cells_volume_flux(const std::vector<SHSurface>& cells, const Eigen::Ref<const Eigen::MatrixXd>& velocity,
                         const SHTransform& grid, int axis, const Communicator& ranks) {
  if (axis < 0 || axis > 2) throw std::invalid_argument("cells_volume_flux: the axis must be 0, 1 or 2");
  const Eigen::Index np = grid.grid().size();
  if (velocity.rows() != np * static_cast<Eigen::Index>(cells.size()) || velocity.cols() != 3)
    throw std::invalid_argument("cells_volume_flux: the velocity has the wrong shape");
  Eigen::VectorXd flux = Eigen::VectorXd::Zero(1);
  for (std::size_t c = 0; c < cells.size(); ++c) {
    const SurfaceGeometry g = cells[c].geometry(grid);
    const Eigen::MatrixXd u = velocity.middleRows(static_cast<Eigen::Index>(c) * np, np);
    const Eigen::ArrayXd normal_velocity = (u.array() * g.normal.array()).rowwise().sum();
    flux[0] += (g.x.col(axis).array() * normal_velocity * g.area_weight.array()).sum();
  }
  ranks.sum(flux);
  return flux[0];
}

}  // namespace rbcflow
