#include "geometry/vessel/vessel_mesh.h"

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

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

TriangleMesh drawable_surface(const VesselMesh& wall) {
  const auto& m = wall.surface;
  TriangleMesh out;
  out.triangles = m.triangles;
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < m.num_points(); ++i) points.push_back(m.points.row(i).transpose());
  std::map<std::pair<int, std::array<long, 3>>, int> copies;  // (node, period shift) -> copy
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    for (int a = 1; a < 3; ++a) {
      const int i = m.triangles(t, a);
      const Eigen::Vector3d d = v.col(a) - m.points.row(i).transpose();
      if (d.norm() == 0.0) continue;
      std::array<long, 3> shift{};
      for (int k = 0; k < 3; ++k) shift[k] = wall.period[k] > 0 ? std::lround(d[k] / wall.period[k]) : 0;
      const auto [it, added] = copies.try_emplace({i, shift}, static_cast<int>(points.size()));
      if (added) points.push_back(v.col(a));
      out.triangles(t, a) = it->second;
    }
  }
  out.points.resize(static_cast<int>(points.size()), 3);
  for (int i = 0; i < static_cast<int>(points.size()); ++i) out.points.row(i) = points[i].transpose();
  return out;
}

}  // namespace rbcflow
