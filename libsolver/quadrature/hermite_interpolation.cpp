#include "hermite_interpolation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace rbcflow {

HermiteInterpolator::HermiteInterpolator(int order, int refinement) {
  if (order < 1 || refinement < 1) throw std::invalid_argument("HermiteInterpolator: bad order or refinement");
  const int n_theta = refinement * order + 1, n_phi = 2 * refinement * order;
  transform_ = std::make_shared<const SHTransform>(order, SphGrid::uniform(n_theta, n_phi), 1);
  dtheta_ = std::numbers::pi / (n_theta - 1);
  dphi_ = 2 * std::numbers::pi / n_phi;
}

HermiteData HermiteInterpolator::node_data(const SHCoeffs& c) const {
  const int k = c.components();
  HermiteData data(transform_->grid().size(), 4 * k);
  const int derivs[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
  for (int d = 0; d < 4; ++d) {
    const Eigen::MatrixXd v = transform_->synthesize(c, derivs[d][0], derivs[d][1]);
    for (int comp = 0; comp < k; ++comp) data.col(4 * comp + d) = v.col(comp);
  }
  return data;
}

namespace {

// The grid cell (i, j) of a point and its offsets (s, t) in [0, 1] within it.
struct GridCell {
  int i, j;
  double s, t;
};

GridCell locate(double theta, double phi, double dtheta, double dphi, int n_theta, int n_phi) {
  const double ti = std::clamp(theta / dtheta, 0.0, double(n_theta - 1));
  const int i = std::min(static_cast<int>(ti), n_theta - 2);
  double pj = phi / dphi;
  pj -= n_phi * std::floor(pj / n_phi);
  const int j = std::min(static_cast<int>(pj), n_phi - 1);
  return {i, j, ti - i, pj - j};
}

}  // namespace

HermiteStencil HermiteInterpolator::stencil(double theta, double phi) const {
  const GridCell c = locate(theta, phi, dtheta_, dphi_, n_theta(), n_phi());
  return {c.i, c.j, hermite_weights(c.s, dtheta_), hermite_weights(c.t, dphi_)};
}

CompactHermiteStencil HermiteInterpolator::compact_stencil(double theta, double phi) const {
  constexpr int kMax = std::numeric_limits<std::uint16_t>::max() + 1;
  if (n_theta() > kMax || n_phi() > kMax)
    throw std::length_error("HermiteInterpolator: a compact stencil indexes at most 65,536 nodes in theta and phi");
  const GridCell c = locate(theta, phi, dtheta_, dphi_, n_theta(), n_phi());
  return {static_cast<std::uint16_t>(c.i), static_cast<std::uint16_t>(c.j), static_cast<float>(c.s),
          static_cast<float>(c.t)};
}

}  // namespace rbcflow
