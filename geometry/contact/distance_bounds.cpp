#include "geometry/contact/distance_bounds.h"

#include <cmath>

namespace rbcflow {

DistanceBounds::DistanceBounds(const TriangleMesh& mesh, const Eigen::Matrix<double, Eigen::Dynamic, 3>& normals,
                               const TriangleAabbTree& tree, double margin, double spacing)
    : spacing_(spacing) {
  box_low_ = mesh.points.colwise().minCoeff().transpose();
  box_high_ = mesh.points.colwise().maxCoeff().transpose();
  low_ = box_low_.array() - margin;
  const Eigen::Vector3d high = box_high_.array() + margin;
  for (int k = 0; k < 3; ++k) count_[k] = static_cast<int>(std::ceil((high[k] - low_[k]) / spacing)) + 1;
  values_.resize(static_cast<std::size_t>(count_[0]) * count_[1] * count_[2]);
  const long planes = static_cast<long>(count_[1]) * count_[2];
#pragma omp parallel for schedule(dynamic, 16)
  for (long jk = 0; jk < planes; ++jk) {
    const int j = static_cast<int>(jk % count_[1]), k = static_cast<int>(jk / count_[1]);
    for (int i = 0; i < count_[0]; ++i) {
      const Eigen::Vector3d c = low_ + spacing * Eigen::Vector3d(i, j, k);
      const TriangleAabbTree::ClosestPoint p = tree.closest_point(c);
      const bool outside = (c - p.point).dot(normals.row(p.triangle).transpose()) >= 0;
      const double sd = outside ? p.distance : -p.distance;
      // Rounded down to single precision: the bound stays a bound.
      float f = static_cast<float>(sd);
      if (static_cast<double>(f) > sd) f = std::nextafter(f, -INFINITY);
      values_[static_cast<std::size_t>(jk) * count_[0] + i] = f;
    }
  }
}

double DistanceBounds::lower(const Eigen::Vector3d& y) const {
  Eigen::Vector3i n;
  for (int k = 0; k < 3; ++k) {
    const double u = (y[k] - low_[k]) / spacing_;
    if (u < 0 || u > count_[k] - 1) {
      // Beyond the grid: at least the distance to the surface's bounding box.
      const Eigen::Vector3d outside = (box_low_ - y).cwiseMax(y - box_high_).cwiseMax(0.0);
      return outside.norm();
    }
    n[k] = static_cast<int>(std::lround(u));
  }
  const Eigen::Vector3d c = low_ + spacing_ * n.cast<double>();
  const std::size_t at = (static_cast<std::size_t>(n[2]) * count_[1] + n[1]) * count_[0] + n[0];
  return static_cast<double>(values_[at]) - (y - c).norm();
}

}  // namespace rbcflow
