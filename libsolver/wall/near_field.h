#pragma once
// Accurate single-layer integrals over the wall triangles near each target (paper section 4):
// a triangle is near when its centroid is within near_factor times its diameter of the target
// (minimum image under the wall's periods). A triangle containing the target (a node, or a
// point on the wall) is split at the target and integrated by Duffy's rule; the other near
// triangles by adaptive subdivision into Gauss-7 pieces. The kernel is the free-space G: the
// periodic remainder G^per - G is smooth and left to the Gauss-7 far-field sum.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <functional>
#include <utility>
#include <vector>

#include "wall_elements.h"

namespace rbcflow {

struct NearField {
  // Both 3 n_targets x 3 n_nodes (index 3 i + k), acting on nodal densities:
  // the accurate integrals over the near triangles, int lambda_a G dS, minus their Gauss-7 sum;
  Eigen::SparseMatrix<double> correction;
  // the accurate integrals alone over the triangles within preconditioner_factor diameters
  // (the target's own star and a few more): sparse enough for a cheap LU (wall_solver.h).
  Eigen::SparseMatrix<double> local;
  // (target, Gauss point) pairs at the same position to 1e-12 of the element size (a target
  // at a centroid), left out of the Gauss-7 sum here as in the far-field sum (wall_operator.h).
  std::vector<std::pair<int, int>> coincident;
};

// `rows` (when given): the targets whose rows are wanted; the others' rows stay empty (their
// coincident pairs are still found, so that every rank snaps the same targets).
NearField near_field(const WallElements& elements, const Eigen::Matrix<double, Eigen::Dynamic, 3>& targets,
                     double near_factor = 3.0, double preconditioner_factor = 1.0,
                     const std::function<bool(int)>& rows = {});

// [M_0 M_1 M_2], M_a = int_T lambda_a(y) G(y - x) dS(y), for triangle vertices v (columns).
Eigen::Matrix<double, 3, 9> element_single_layer(const Eigen::Matrix3d& v, const Eigen::Vector3d& x);

}  // namespace rbcflow
