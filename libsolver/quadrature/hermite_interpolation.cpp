#include "hermite_interpolation.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rbcflow {
namespace {

// Cubic Hermite basis on [0, 1]: value and slope at the left (0) and right (1) ends.
void hermite_basis(double s, double h, double v[2], double d[2]) {
  const double s2 = s * s, s3 = s2 * s;
  v[0] = 2 * s3 - 3 * s2 + 1;
  v[1] = -2 * s3 + 3 * s2;
  d[0] = h * (s3 - 2 * s2 + s);
  d[1] = h * (s3 - s2);
}

}  // namespace

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

HermiteStencil HermiteInterpolator::stencil(double theta, double phi) const {
  const double ti = std::clamp(theta / dtheta_, 0.0, double(n_theta() - 1));
  const int i = std::min(static_cast<int>(ti), n_theta() - 2);
  double pj = phi / dphi_;
  pj -= n_phi() * std::floor(pj / n_phi());
  const int j = std::min(static_cast<int>(pj), n_phi() - 1);
  const double s = ti - i, t = pj - j;
  double vs[2], ds[2], vt[2], dt[2];
  hermite_basis(s, dtheta_, vs, ds);
  hermite_basis(t, dphi_, vt, dt);
  HermiteStencil st;
  st.i = i;
  st.j = j;
  st.theta_w = {vs[0], ds[0], vs[1], ds[1]};
  st.phi_w = {vt[0], dt[0], vt[1], dt[1]};
  return st;
}

}  // namespace rbcflow
