#pragma once
// A surface of linear triangles: points and counter-clockwise (outward-normal) triangles.
#include <Eigen/Core>

namespace rbcflow {

struct TriangleMesh {
  Eigen::Matrix<double, Eigen::Dynamic, 3> points;
  Eigen::Matrix<int, Eigen::Dynamic, 3> triangles;

  int num_points() const { return static_cast<int>(points.rows()); }
  int num_triangles() const { return static_cast<int>(triangles.rows()); }
};

// Volume enclosed by a closed, outward-oriented mesh (divergence theorem); positive when the
// triangles are oriented outward.
double enclosed_volume(const TriangleMesh& mesh);

// The winding number of a closed, outward-oriented mesh about x: the solid angle its triangles
// subtend at x over 4 pi (Van Oosterom & Strackee 1983), 1 inside and 0 outside to rounding,
// however the surface folds.
double winding_number(const TriangleMesh& mesh, const Eigen::Vector3d& x);

}  // namespace rbcflow
