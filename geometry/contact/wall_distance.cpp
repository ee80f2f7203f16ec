#include "geometry/contact/wall_distance.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rbcflow {
namespace {

// Unwrapped triangles, copied by -1, 0, +1 periods along each periodic axis.
TriangleMesh periodic_images(const VesselMesh& wall) {
  std::vector<Eigen::Vector3d> shifts{Eigen::Vector3d::Zero()};
  for (int d = 0; d < 3; ++d) {
    if (wall.period[d] <= 0) continue;
    const std::size_t n = shifts.size();
    for (int k : {-1, 1}) {
      for (std::size_t s = 0; s < n; ++s) shifts.push_back(shifts[s] + k * wall.period[d] * Eigen::Vector3d::Unit(d));
    }
  }
  const int nt = wall.surface.num_triangles();
  TriangleMesh m;
  m.points.resize(3 * nt * static_cast<int>(shifts.size()), 3);
  m.triangles.resize(nt * static_cast<int>(shifts.size()), 3);
  int t_out = 0;
  for (const Eigen::Vector3d& shift : shifts) {
    for (int t = 0; t < nt; ++t, ++t_out) {
      const Eigen::Matrix3d v = triangle_vertices(wall, t);
      for (int a = 0; a < 3; ++a) {
        m.points.row(3 * t_out + a) = (v.col(a) + shift).transpose();
        m.triangles(t_out, a) = 3 * t_out + a;
      }
    }
  }
  return m;
}

}  // namespace

WallDistance::WallDistance(const VesselMesh& wall)
    : period_(wall.period), images_(periodic_images(wall)), tree_(images_) {}

WallDistance::Query WallDistance::closest(const Eigen::Vector3d& x) const {
  Eigen::Vector3d wrapped = x;
  for (int d = 0; d < 3; ++d)
    if (period_[d] > 0) wrapped[d] -= period_[d] * std::floor(x[d] / period_[d]);
  const TriangleAabbTree::ClosestPoint c = tree_.closest_point(wrapped);
  const auto tri = images_.triangles.row(c.triangle);
  const Eigen::Vector3d p0 = images_.points.row(tri[0]).transpose();
  const Eigen::Vector3d n =
      (images_.points.row(tri[1]).transpose() - p0).cross(images_.points.row(tri[2]).transpose() - p0).normalized();
  Query q;
  q.point = c.point + (x - wrapped);
  q.normal = n;
  q.signed_distance = (wrapped - c.point).dot(n) >= 0 ? c.distance : -c.distance;
  return q;
}

double smallest_wall_distance(const WallDistance& wall, const std::vector<Eigen::MatrixX3d>& point_sets) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const Eigen::MatrixX3d& points : point_sets) {
    if (points.rows() == 0) continue;
    const Eigen::Vector3d centre = points.colwise().mean().transpose();
    const double radius = (points.rowwise() - centre.transpose()).rowwise().norm().maxCoeff();
    const double at_centre = wall.closest(centre).signed_distance;
    if (at_centre - radius >= smallest) continue;
    Eigen::Vector3d anchor = centre;
    double anchor_distance = at_centre;
    for (Eigen::Index p = 0; p < points.rows(); ++p) {
      const Eigen::Vector3d x = points.row(p).transpose();
      // Distance to the wall is 1-Lipschitz: no smaller than the anchor's less the step.
      if (anchor_distance - (x - anchor).norm() >= smallest) continue;
      const double d = wall.closest(x).signed_distance;
      smallest = std::min(smallest, d);
      anchor = x;
      anchor_distance = d;
    }
  }
  return smallest;
}

double lumen_volume(const VesselMesh& wall) {
  int free_axes = 0;
  for (int d = 0; d < 3; ++d) free_axes += wall.period[d] > 0 ? 0 : 1;
  if (free_axes == 0) throw std::invalid_argument("lumen_volume: a wall periodic along all three axes");
  double volume = 0;
  for (int t = 0; t < wall.surface.num_triangles(); ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    // Normals point into the lumen: the outward area vector of the lumen is minus theirs.
    const Eigen::Vector3d outward_area = -0.5 * (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0));
    const Eigen::Vector3d centroid = v.rowwise().mean();
    for (int d = 0; d < 3; ++d)
      if (wall.period[d] <= 0) volume += centroid[d] * outward_area[d];
  }
  return volume / free_axes;
}

}  // namespace rbcflow
