#include "libsolver/stepper/cell_measures.h"

#include <span>
#include <stdexcept>

#include "geometry/surface/inertia_ellipsoid.h"
#include "geometry/surface/sh_surface.h"
#include "libsolver/parallel/share_blocks.h"

namespace rbcflow {

std::vector<CellMeasures> cell_measures(const std::vector<Cell>& cells, const SHTransform& transform,
                                        const Eigen::MatrixXd& owned_velocity, const CellOwners& owners,
                                        const Communicator& ranks) {
  if (owners.order.size() != cells.size()) throw std::invalid_argument("cell_measures: not one owner a cell");
  const int first = owners.first[ranks.rank()], end = owners.first[ranks.rank() + 1];
  const Eigen::Index np = transform.grid().size();
  if (owned_velocity.rows() != (end - first) * np || owned_velocity.cols() != 3)
    throw std::invalid_argument("cell_measures: the velocity is not the rows of this rank's cells");
  std::vector<CellMeasures> m(cells.size());
#pragma omp parallel for schedule(dynamic)
  for (int k = first; k < end; ++k) {
    CellMeasures& x = m[static_cast<std::size_t>(owners.order[k])];
    const SurfaceGeometry g = cells[static_cast<std::size_t>(owners.order[k])].shape.geometry(transform);
    x.centroid = volume_centroid(g);
    x.velocity = (owned_velocity.middleRows((k - first) * np, np).transpose() * g.area_weight) / g.area_weight.sum();
    const InertiaEllipsoid e = inertia_ellipsoid(g);
    x.longest_axis = e.axes.col(2);
    x.volume = enclosed_volume(g);
    x.area = surface_area(g);
    x.taylor_deformation = e.taylor_deformation();
  }
  std::vector<std::vector<std::span<double>>> items;  // in owner order: their blocks are share_blocks'
  for (const int c : owners.order) {
    CellMeasures& x = m[static_cast<std::size_t>(c)];
    items.push_back({std::span<double>(x.centroid.data(), 3), std::span<double>(x.velocity.data(), 3),
                     std::span<double>(x.longest_axis.data(), 3), std::span<double>(&x.volume, 1),
                     std::span<double>(&x.area, 1), std::span<double>(&x.taylor_deformation, 1)});
  }
  share_blocks(ranks, items);
  return m;
}

}  // namespace rbcflow
