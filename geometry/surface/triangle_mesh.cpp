#include "geometry/surface/triangle_mesh.h"

#include <Eigen/Geometry>

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

}  // namespace rbcflow
