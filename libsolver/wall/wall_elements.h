#pragma once
// The wall's linear boundary elements (paper section 4): the force density is linear on each
// triangle, f(y) = sum_a lambda_a(y) f_{node a}, integrated by the 7-point Gauss rule.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <vector>

#include "geometry/vessel/vessel_mesh.h"

namespace rbcflow {

struct WallElements {
  explicit WallElements(const VesselMesh& wall);

  VesselMesh wall;
  std::vector<Eigen::Matrix3d> vertices;  // per triangle, unwrapped, one vertex per column
  Eigen::VectorXd areas;                  // per triangle
  Eigen::VectorXd diameters;              // per triangle: the longest edge
  // The 7 Gauss points of every triangle (row 7 t + q) and their area weights.
  Eigen::Matrix<double, Eigen::Dynamic, 3> points;
  Eigen::VectorXd weights;
  Eigen::VectorXd node_areas;  // integral of each node's hat function (A / 3 per triangle)

  int num_nodes() const { return wall.surface.num_points(); }
  int num_triangles() const { return wall.surface.num_triangles(); }

  // The density at the Gauss points times their weights, from nodal densities (one row each).
  Eigen::Matrix<double, Eigen::Dynamic, 3> weighted_density(
      const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodal) const;
  // weighted_density as a matrix: Gauss points (row 7 t + q) x nodes.
  Eigen::SparseMatrix<double, Eigen::RowMajor> density_map() const;
  // integral over the wall of f dS.
  Eigen::Vector3d total(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodal) const;
};

// Nodal fields (one row per node) as flat vectors, index 3 i + k, and back.
Eigen::VectorXd to_vector(const Eigen::Matrix<double, Eigen::Dynamic, 3>& field);
Eigen::Matrix<double, Eigen::Dynamic, 3> to_field(const Eigen::VectorXd& flat);

}  // namespace rbcflow
