#include "geometry/vessel/mesh_check.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace rbcflow {

namespace {

std::string edge_name(int a, int b) {
  std::string s("between nodes ");
  s.append(std::to_string(a)).append(" and ").append(std::to_string(b));
  return s;
}

void check_indices(const TriangleMesh& m) {
  if (m.num_points() == 0 || m.num_triangles() == 0)
    throw std::runtime_error("wall mesh is empty (no nodes or no triangles)");
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) {
      const int i = m.triangles(t, a);
      if (i < 0 || i >= m.num_points())
        throw std::runtime_error("wall mesh triangle " + std::to_string(t) +
                                 " refers to node " + std::to_string(i) + " which does not exist");
    }
}

Eigen::Vector3d unit_normal(const VesselMesh& wall, int t) {
  const Eigen::Matrix3d v = triangle_vertices(wall, t);
  return (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).normalized();
}

// Directed edge uses: each undirected edge must appear once in each direction. Returns the
// largest fold (degrees) between the two triangles of an edge.
double check_edges(const VesselMesh& wall) {
  const TriangleMesh& m = wall.surface;
  std::map<std::pair<int, int>, std::vector<int>> uses;  // (min, max) -> +-(t + 1)
  for (int t = 0; t < m.num_triangles(); ++t)
    for (int a = 0; a < 3; ++a) {
      const int i = m.triangles(t, a), j = m.triangles(t, (a + 1) % 3);
      uses[{std::min(i, j), std::max(i, j)}].push_back(i < j ? t + 1 : -(t + 1));
    }
  double largest_fold = 0.0;
  for (const auto& [edge, ts] : uses) {
    const std::string name = edge_name(edge.first, edge.second);
    if (ts.size() == 1)
      throw std::runtime_error("wall mesh has a hole: the edge " + name +
                               " belongs to one triangle only (" + std::to_string(std::abs(ts[0]) - 1) + ")");
    if (ts.size() > 2)
      throw std::runtime_error("wall mesh is not manifold: the edge " + name + " belongs to " +
                               std::to_string(ts.size()) + " triangles");
    if ((ts[0] > 0) == (ts[1] > 0))
      throw std::runtime_error("wall mesh is not consistently oriented: triangles " +
                               std::to_string(std::abs(ts[0]) - 1) + " and " +
                               std::to_string(std::abs(ts[1]) - 1) + " traverse the edge " +
                               name + " in the same direction (a flipped triangle)");
    const double cosine = unit_normal(wall, std::abs(ts[0]) - 1).dot(unit_normal(wall, std::abs(ts[1]) - 1));
    largest_fold = std::max(largest_fold, std::acos(std::clamp(cosine, -1.0, 1.0)));
  }
  return largest_fold * 180.0 / std::numbers::pi;
}

void check_duplicates(const VesselMesh& wall, double tolerance) {
  const auto& p = wall.surface.points;
  std::vector<int> order(p.rows());
  for (int i = 0; i < p.rows(); ++i) order[i] = i;
  // Sort by the wrapped first coordinate, then compare neighbours within the tolerance.
  auto key = [&](int i) {
    const double x = p(i, 0), l = wall.period[0];
    return l > 0 ? x - l * std::floor(x / l) : x;
  };
  std::sort(order.begin(), order.end(), [&](int a, int b) { return key(a) < key(b); });
  const int n = static_cast<int>(order.size());
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n && key(order[b]) - key(order[a]) <= tolerance; ++b) {
      const Eigen::Vector3d d = (p.row(order[b]) - p.row(order[a])).transpose();
      if (minimum_image(d, wall.period).norm() <= tolerance)
        throw std::runtime_error("wall mesh has duplicate nodes " + std::to_string(order[a]) +
                                 " and " + std::to_string(order[b]) + " at the same position");
    }
}

}  // namespace

MeshQuality check_mesh(const VesselMesh& wall) {
  const TriangleMesh& m = wall.surface;
  check_indices(m);
  const double extent = (m.points.colwise().maxCoeff() - m.points.colwise().minCoeff()).norm();
  check_duplicates(wall, 1e-10 * extent);
  MeshQuality q;
  q.min_angle_deg = 180.0;
  q.min_edge = INFINITY;
  for (int t = 0; t < m.num_triangles(); ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    const double area = 0.5 * (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).norm();
    double longest = 0.0;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e1 = v.col((a + 1) % 3) - v.col(a), e2 = v.col((a + 2) % 3) - v.col(a);
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2)) * 180.0 / std::numbers::pi;
      q.min_angle_deg = std::min(q.min_angle_deg, angle);
      q.min_edge = std::min(q.min_edge, e1.norm());
      longest = std::max(longest, e1.norm());
    }
    q.max_edge = std::max(q.max_edge, longest);
    if (!(area > 1e-12 * longest * longest))
      throw std::runtime_error("wall mesh triangle " + std::to_string(t) +
                               " is degenerate (zero area)");
    q.area += area;
  }
  q.max_fold_deg = check_edges(wall);
  return q;
}

}  // namespace rbcflow
