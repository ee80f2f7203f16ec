#pragma once
// Shared set-up of the quadrature validations (section 8 identities, REFERENCES section 1).
#include <cmath>
#include <memory>
#include <numbers>

#include "geometry/reference_shapes.h"
#include "libsolver/quadrature/singular_quadrature.h"

namespace rbcflow::quadrature_test {

// The options with which the acceptance figures are reached (see the issue note): a patch
// three times the paper's radius, 24 x 96 patch points, Hermite grid refinement 4.
inline QuadratureOptions accurate_options() {
  QuadratureOptions o;
  o.patch_radius_factor = 3.0;
  o.radial_points = 24;
  o.angular_points = 96;
  o.spline_refinement = 4;
  return o;
}

// The outward normal's expansion to order L (it is not band-limited).
inline SHCoeffs normal_coeffs(const SHCoeffs& x, int L) {
  const SHTransform t(L, SphGrid::gauss(L), 2);
  return t.analyze(surface_geometry(x, t).normal);
}

struct IdentityErrors {
  double single, double_;  // area-weighted L2 norms of the errors of (38) and (39) / (4 pi |U|)
};

// L2 errors of the single-layer identity (38) and double-layer identity (39) at every node,
// free-space kernels.
inline IdentityErrors section8_identity_errors(const SHSurface& s, int N, const QuadratureOptions& o) {
  auto cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N), o);
  const SourceNodes& nodes = cell->nodes();
  const Eigen::MatrixXd sl = free_space_layer_on_nodes(cell, Layer::single, nodes.normal, normal_coeffs(s.coeffs(), 2 * N));
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(nodes.size(), 3);
  U.col(0).setConstant(1.0);
  U.col(1).setConstant(0.5);
  const Eigen::MatrixXd dl = free_space_layer_on_nodes(cell, Layer::double_, U) + 4 * std::numbers::pi * U;
  double es = 0, ed = 0;
  for (int p = 0; p < nodes.size(); ++p) {
    es += nodes.weight[p] * sl.row(p).squaredNorm();
    ed += nodes.weight[p] * dl.row(p).squaredNorm();
  }
  const double area = nodes.weight.sum();
  return {std::sqrt(es / area), std::sqrt(ed / area) / (4 * std::numbers::pi * U.row(0).norm())};
}

}  // namespace rbcflow::quadrature_test
