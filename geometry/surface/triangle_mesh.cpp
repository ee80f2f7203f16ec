#include "geometry/surface/triangle_mesh.h"

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

namespace rbcflow {

double enclosed_volume(const TriangleMesh& mesh) {
  double v = 0.0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d p0 = mesh.points.row(mesh.triangles(t, 0));
    const Eigen::Vector3d p1 = mesh.points.row(mesh.triangles(t, 1));
    const Eigen::Vector3d p2 = mesh.points.row(mesh.triangles(t, 2));
    v += p0.dot(p1.cross(p2));
  }
  return v / 6.0;
}

double winding_number(const TriangleMesh& mesh, const Eigen::Vector3d& x) {
  double solid_angle = 0;
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    const Eigen::Vector3d a = mesh.points.row(mesh.triangles(t, 0)).transpose() - x;
    const Eigen::Vector3d b = mesh.points.row(mesh.triangles(t, 1)).transpose() - x;
    const Eigen::Vector3d c = mesh.points.row(mesh.triangles(t, 2)).transpose() - x;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    solid_angle += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return solid_angle / (4 * std::numbers::pi);
}

}  // namespace rbcflow
