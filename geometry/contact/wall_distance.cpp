#include "geometry/contact/wall_distance.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
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
    : period_(wall.period), triangles_(wall.surface.triangles), images_(periodic_images(wall)), tree_(images_) {
  const int nt = wall.surface.num_triangles();
  face_normals_.resize(nt, 3);
  node_normals_ = Eigen::Matrix<double, Eigen::Dynamic, 3>::Zero(wall.surface.num_points(), 3);
  for (int t = 0; t < nt; ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    const Eigen::Vector3d n = (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).normalized();
    face_normals_.row(t) = n.transpose();
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e1 = v.col((a + 1) % 3) - v.col(a), e2 = v.col((a + 2) % 3) - v.col(a);
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      node_normals_.row(triangles_(t, a)) += angle * n.transpose();
    }
  }
  // Edge a of a triangle joins its nodes a + 1 and a + 2; its pseudonormal adds the normal of
  // the triangle across it.
  std::map<std::pair<int, int>, std::pair<int, int>> edges;  // sorted nodes -> (triangle, edge)
  edge_normals_.resize(3 * nt, 3);
  for (int t = 0; t < nt; ++t) {
    for (int a = 0; a < 3; ++a) {
      const int i = triangles_(t, (a + 1) % 3), j = triangles_(t, (a + 2) % 3);
      const auto key = std::minmax(i, j);
      edge_normals_.row(3 * t + a) = face_normals_.row(t);
      const auto [it, added] = edges.emplace(key, std::pair{t, a});
      if (added) continue;
      const auto [u, b] = it->second;
      edge_normals_.row(3 * t + a) += face_normals_.row(u);
      edge_normals_.row(3 * u + b) += face_normals_.row(t);
    }
  }
}

Eigen::Vector3d WallDistance::pseudonormal(int t, const Eigen::Vector3d& b) const {
  constexpr double kOnEdge = 1e-9;  // barycentric coordinate below which the point is on the edge
  int zeros = 0, last_zero = 0, largest = 0;
  for (int a = 0; a < 3; ++a) {
    if (b[a] < kOnEdge) {
      ++zeros;
      last_zero = a;
    }
    if (b[a] > b[largest]) largest = a;
  }
  if (zeros >= 2) return node_normals_.row(triangles_(t, largest)).transpose();
  if (zeros == 1) return edge_normals_.row(3 * t + last_zero).transpose();
  return face_normals_.row(t).transpose();
}

WallDistance::Query WallDistance::closest(const Eigen::Vector3d& x) const {
  Eigen::Vector3d wrapped = x;
  for (int d = 0; d < 3; ++d)
    if (period_[d] > 0) wrapped[d] -= period_[d] * std::floor(x[d] / period_[d]);
  const TriangleAabbTree::ClosestPoint c = tree_.closest_point(wrapped);
  const auto tri = images_.triangles.row(c.triangle);
  const Eigen::Vector3d p0 = images_.points.row(tri[0]).transpose();
  const Eigen::Vector3d e1 = images_.points.row(tri[1]).transpose() - p0, e2 = images_.points.row(tri[2]).transpose() - p0;
  // Barycentric coordinates of the closest point (least squares in the triangle's plane).
  const Eigen::Vector3d d = c.point - p0;
  const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2), det = a11 * a22 - a12 * a12;
  const double u = (a22 * d.dot(e1) - a12 * d.dot(e2)) / det, v = (a11 * d.dot(e2) - a12 * d.dot(e1)) / det;
  const Eigen::Vector3d n = pseudonormal(c.triangle % static_cast<int>(triangles_.rows()), Eigen::Vector3d(1 - u - v, u, v));
  Query q;
  q.point = c.point + (x - wrapped);
  q.normal = n.normalized();
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
