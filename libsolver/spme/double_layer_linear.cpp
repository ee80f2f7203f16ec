#include "double_layer_linear.h"

#include <numbers>
#include <stdexcept>

namespace rbcflow {

PointField double_layer_linear_part(const PeriodicBox& box, const PointField& sources,
                                    const PointField& q, const PointField& normals,
                                    const PointField& targets) {
  if (q.rows() != sources.rows() || normals.rows() != sources.rows())
    throw std::invalid_argument(
        "double-layer linear part: sources, density and normals must have the same rows");
  const Eigen::VectorXd qn = (q.array() * normals.array()).rowwise().sum();
  const double flux = qn.sum();                                // sum_s q_s . n_s
  const Eigen::RowVector3d moment = qn.transpose() * sources;  // sum_s (q_s . n_s) x_s
  const double c = -8.0 * std::numbers::pi / box.volume();
  PointField u = (-c * flux) * targets;
  u.rowwise() += c * moment;
  return u;
}

}  // namespace rbcflow
