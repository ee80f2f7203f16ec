#include "triangle_rules.h"

#include <cmath>

#include "geometry/sph/gauss_legendre.h"

namespace rbcflow {

namespace {

TriangleRule make_gauss7() {
  TriangleRule r;
  r.barycentric.resize(7, 3);
  r.weights.resize(7);
  r.barycentric.row(0).setConstant(1.0 / 3.0);
  r.weights[0] = 0.225;
  const double a[2] = {0.059715871789770, 0.797426985353087};
  const double b[2] = {0.470142064105115, 0.101286507323456};
  const double w[2] = {0.132394152788506, 0.125939180544827};
  for (int k = 0; k < 2; ++k)
    for (int p = 0; p < 3; ++p) {
      const int row = 1 + 3 * k + p;
      r.barycentric.row(row).setConstant(b[k]);
      r.barycentric(row, p) = a[k];
      r.weights[row] = w[k];
    }
  return r;
}

}  // namespace

const TriangleRule& gauss7_rule() {
  static const TriangleRule rule = make_gauss7();
  return rule;
}

TriangleRule duffy_rule(int n) {
  const GaussLegendreRule gl = gauss_legendre(n);
  TriangleRule r;
  r.barycentric.resize(n * n, 3);
  r.weights.resize(n * n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u = 0.5 * (1.0 + std::cos(gl.theta[i])), w = 0.5 * (1.0 + std::cos(gl.theta[j]));
      // y = (1 - u) v0 + u (1 - w) v1 + u w v2; dS = 2 A u du dw, weights relative to A.
      r.barycentric.row(i * n + j) << 1.0 - u, u * (1.0 - w), u * w;
      r.weights[i * n + j] = 2.0 * u * 0.25 * gl.weights[i] * gl.weights[j];
    }
  return r;
}

}  // namespace rbcflow
