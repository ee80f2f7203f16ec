#include "vessel_mesh.h"

#include <cmath>

namespace rbcflow {

Eigen::Vector3d minimum_image(const Eigen::Vector3d& d, const Eigen::Vector3d& period) {
  Eigen::Vector3d r = d;
  for (int k = 0; k < 3; ++k)
    if (period[k] > 0) r[k] -= period[k] * std::round(r[k] / period[k]);
  return r;
}

Eigen::Matrix3d triangle_vertices(const VesselMesh& wall, int t) {
  const auto& m = wall.surface;
  Eigen::Matrix3d v;
  v.col(0) = m.points.row(m.triangles(t, 0)).transpose();
  for (int a = 1; a < 3; ++a)
    v.col(a) = v.col(0) + minimum_image(m.points.row(m.triangles(t, a)).transpose() - v.col(0),
                                        wall.period);
  return v;
}

}  // namespace rbcflow
