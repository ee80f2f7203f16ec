#include "double_layer_linear.h"

#include <numbers>
#include <stdexcept>
#include <string>

namespace rbcflow {

Eigen::RowVector3d double_layer_linear_part(const PeriodicBox& box, const PointField& sources, const PointField& q,
                                            const PointField& normals, int points_per_surface) {
  if (q.rows() != sources.rows() || normals.rows() != sources.rows())
    throw std::invalid_argument("double-layer linear part: sources, density and normals must have the same rows");
  if (points_per_surface < 1 || sources.rows() % points_per_surface != 0)
    throw std::invalid_argument("double-layer linear part: " + std::to_string(sources.rows()) +
                                " sources are not whole surfaces of " + std::to_string(points_per_surface) +
                                " points");
  const Eigen::VectorXd qn = (q.array() * normals.array()).rowwise().sum();
  Eigen::RowVector3d moment = Eigen::RowVector3d::Zero();  // sum_S sum_s (q_s . n_s) (x_s - c_S)
  for (Eigen::Index first = 0; first < sources.rows(); first += points_per_surface) {
    const auto x = sources.middleRows(first, points_per_surface);
    const Eigen::RowVector3d centre = x.colwise().mean();
    moment += qn.segment(first, points_per_surface).transpose() * (x.rowwise() - centre);
  }
  return (-8.0 * std::numbers::pi / box.volume()) * moment;
}

}  // namespace rbcflow
