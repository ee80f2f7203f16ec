#pragma once
// Gauss-Legendre quadrature on [-1, 1], expressed in colatitude theta = acos(x) so that nodes
// near the poles keep full relative precision.
#include <Eigen/Core>

namespace rbcflow {

struct GaussLegendreRule {
  Eigen::VectorXd theta;    // colatitudes, ascending in (0, pi): the roots of P_n(cos theta)
  Eigen::VectorXd weights;  // weights for integrals over x = cos(theta) in [-1, 1]
};

// The n-point rule, refined by Newton's method in theta to full double precision.
GaussLegendreRule gauss_legendre(int n);

}  // namespace rbcflow
