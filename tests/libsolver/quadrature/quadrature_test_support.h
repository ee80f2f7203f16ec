#pragma once
// Shared set-up of the quadrature validations (section 8 identities, REFERENCES section 1).
#include <cmath>
#include <memory>
#include <numbers>

#include "geometry/surface/reference_shapes.h"
#include "libsolver/quadrature/singular_quadrature.h"
#include "libsolver/spme/double_layer_linear.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/spme/ewald_plan.h"

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

// The constant density of the double-layer identity (39).
inline Eigen::MatrixXd constant_density(int n) {
  Eigen::MatrixXd U = Eigen::MatrixXd::Zero(n, 3);
  U.col(0).setConstant(1.0);
  U.col(1).setConstant(0.5);
  return U;
}

// Area-weighted L2 norms of the identity residuals sl (single layer of n) and dl (double layer
// of U plus 4 pi U) over the nodes.
inline IdentityErrors identity_errors(const SourceNodes& nodes, const Eigen::MatrixXd& sl, const Eigen::MatrixXd& dl,
                                      const Eigen::MatrixXd& U) {
  double es = 0, ed = 0;
  for (int p = 0; p < nodes.size(); ++p) {
    es += nodes.weight[p] * sl.row(p).squaredNorm();
    ed += nodes.weight[p] * dl.row(p).squaredNorm();
  }
  const double area = nodes.weight.sum();
  return {std::sqrt(es / area), std::sqrt(ed / area) / (4 * std::numbers::pi * U.row(0).norm())};
}

// L2 errors of the single-layer identity (38) and double-layer identity (39) at every node,
// free-space kernels.
inline IdentityErrors section8_identity_errors(const SHSurface& s, int N, const QuadratureOptions& o) {
  auto cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N), o);
  const SourceNodes& nodes = cell->nodes();
  const Eigen::MatrixXd sl = free_space_layer_on_nodes(cell, Layer::single, nodes.normal, normal_coeffs(s.coeffs(), 2 * N));
  const Eigen::MatrixXd U = constant_density(nodes.size());
  const Eigen::MatrixXd dl = free_space_layer_on_nodes(cell, Layer::double_, U) + 4 * std::numbers::pi * U;
  return identity_errors(nodes, sl, dl, U);
}

// The same identities with the periodic Ewald sums in `box` (section 5.3): SPME + real-space
// sums over the nodes, the singular corrections built with the real-space kernels (24) and
// (27), and the linear part of eq. (3) for the double layer. Both identities keep their
// free-space values on the surface (G^per is divergence-free; with the linear part the double
// layer of a constant jumps by the same -8 pi); the errors differ from the free-space ones
// only by how the regular rule integrates the smooth SPME part.
inline IdentityErrors section8_identity_errors_periodic(const SHSurface& s, int N, const QuadratureOptions& o,
                                                        const PeriodicBox& box, double tolerance) {
  auto cell = std::make_shared<const CellQuadratureGeometry>(s.coeffs(), CellGrids::make(N, N), o);
  const SourceNodes& nodes = cell->nodes();
  const auto plan = [&](EwaldKernel kernel) {
    const EwaldChoice c = choose_ewald_parameters(kernel, tolerance, box, nodes.size());
    return EwaldPlan(std::make_shared<const SpmeGrid>(box, c.parameters), nodes.x);
  };
  EwaldPlan single = plan(EwaldKernel::stokeslet), dbl = plan(EwaldKernel::stresslet);
  const PointField weighted_normals = nodes.normal.array().colwise() * nodes.weight.array();
  const LayerCorrection single_correction(cell, LayerKernel{Layer::single, single.xi()}, cell->node_targets());
  const Eigen::MatrixXd sl = single.single_layer(weighted_normals) +
                             single_correction.apply(nodes.normal, normal_coeffs(s.coeffs(), 2 * N));
  const Eigen::MatrixXd U = constant_density(nodes.size());
  const PointField q = U.array().colwise() * nodes.weight.array();
  const LayerCorrection double_correction(cell, LayerKernel{Layer::double_, dbl.xi()}, cell->node_targets());
  Eigen::MatrixXd dl = dbl.double_layer(q, nodes.normal) + double_correction.apply(U) + 4 * std::numbers::pi * U;
  dl.rowwise() += double_layer_linear_part(box, nodes.x, q, nodes.normal, static_cast<int>(nodes.x.rows()));
  return identity_errors(nodes, sl, dl, U);
}

}  // namespace rbcflow::quadrature_test
