#pragma once
// Quadrature rules on a triangle for the linear wall elements (paper section 4): points as
// barycentric coordinates (one row each), weights summing to 1 (multiply by the area).
#include <Eigen/Core>

namespace rbcflow {

struct TriangleRule {
  Eigen::Matrix<double, Eigen::Dynamic, 3> barycentric;
  Eigen::VectorXd weights;
};

// The 7-point Gauss rule (Dunavant 1985, degree 5).
const TriangleRule& gauss7_rule();

// Duffy's rule (Duffy 1982) for an integrand ~ 1/r at vertex 0: the square [0,1]^2 mapped onto
// the triangle by y = v0 + u (v1 - v0) + u w (v2 - v1), whose Jacobian 2 A u cancels the
// singularity; n x n Gauss-Legendre points on the square.
TriangleRule duffy_rule(int n);

}  // namespace rbcflow
