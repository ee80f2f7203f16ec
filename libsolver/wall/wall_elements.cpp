#include "wall_elements.h"

#include <Eigen/Geometry>
#include <vector>

#include "triangle_rules.h"

namespace rbcflow {

WallElements::WallElements(const VesselMesh& w) : wall(w) {
  const int nt = num_triangles();
  const TriangleRule& rule = gauss7_rule();
  vertices.resize(nt);
  areas.resize(nt);
  diameters.resize(nt);
  points.resize(7 * nt, 3);
  weights.resize(7 * nt);
  node_areas = Eigen::VectorXd::Zero(num_nodes());
  for (int t = 0; t < nt; ++t) {
    const Eigen::Matrix3d v = triangle_vertices(wall, t);
    vertices[t] = v;
    areas[t] = 0.5 * (v.col(1) - v.col(0)).cross(v.col(2) - v.col(0)).norm();
    diameters[t] = std::max({(v.col(1) - v.col(0)).norm(), (v.col(2) - v.col(1)).norm(),
                             (v.col(0) - v.col(2)).norm()});
    for (int q = 0; q < 7; ++q) {
      points.row(7 * t + q) = (v * rule.barycentric.row(q).transpose()).transpose();
      weights[7 * t + q] = areas[t] * rule.weights[q];
    }
    for (int a = 0; a < 3; ++a) node_areas[wall.surface.triangles(t, a)] += areas[t] / 3.0;
  }
}

Eigen::Matrix<double, Eigen::Dynamic, 3> WallElements::weighted_density(
    const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodal) const {
  const TriangleRule& rule = gauss7_rule();
  Eigen::Matrix<double, Eigen::Dynamic, 3> out(points.rows(), 3);
  for (int t = 0; t < num_triangles(); ++t)
    for (int q = 0; q < 7; ++q) {
      Eigen::RowVector3d f = Eigen::RowVector3d::Zero();
      for (int a = 0; a < 3; ++a) f += rule.barycentric(q, a) * nodal.row(wall.surface.triangles(t, a));
      out.row(7 * t + q) = weights[7 * t + q] * f;
    }
  return out;
}

Eigen::SparseMatrix<double, Eigen::RowMajor> WallElements::density_map() const {
  const TriangleRule& rule = gauss7_rule();
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(21 * static_cast<std::size_t>(num_triangles()));
  for (int t = 0; t < num_triangles(); ++t)
    for (int q = 0; q < 7; ++q)
      for (int a = 0; a < 3; ++a)
        entries.emplace_back(7 * t + q, wall.surface.triangles(t, a), weights[7 * t + q] * rule.barycentric(q, a));
  Eigen::SparseMatrix<double, Eigen::RowMajor> map(points.rows(), num_nodes());
  map.setFromTriplets(entries.begin(), entries.end());
  return map;
}

Eigen::Vector3d WallElements::total(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodal) const {
  return (node_areas.transpose() * nodal).transpose();
}

Eigen::VectorXd to_vector(const Eigen::Matrix<double, Eigen::Dynamic, 3>& field) {
  Eigen::VectorXd flat(3 * field.rows());
  for (Eigen::Index i = 0; i < field.rows(); ++i) flat.segment<3>(3 * i) = field.row(i).transpose();
  return flat;
}

Eigen::Matrix<double, Eigen::Dynamic, 3> to_field(const Eigen::VectorXd& flat) {
  Eigen::Matrix<double, Eigen::Dynamic, 3> field(flat.size() / 3, 3);
  for (Eigen::Index i = 0; i < field.rows(); ++i) field.row(i) = flat.segment<3>(3 * i).transpose();
  return field;
}

}  // namespace rbcflow
