#include "geometry/sph/gauss_legendre.h"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rbcflow {
namespace {

// P_n(cos t) and dP_n(cos t)/dt by the three-term recurrence.
void legendre_and_theta_derivative(int n, double t, double& p, double& dp_dt) {
  const double x = std::cos(t);
  double p0 = 1.0, p1 = x;
  for (int k = 2; k <= n; ++k) {
    const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
    p0 = p1;
    p1 = p2;
  }
  p = p1;
  // (1 - x^2) P_n'(x) = n (P_{n-1} - x P_n), and dP/dt = -sin(t) P'(x).
  dp_dt = -n * (p0 - x * p1) / std::sin(t);
}

}  // namespace

GaussLegendreRule gauss_legendre(int n) {
  if (n < 1) throw std::invalid_argument("gauss_legendre: need at least one node");
  GaussLegendreRule rule;
  rule.theta.resize(n);
  rule.weights.resize(n);
  const double pi = std::numbers::pi;
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double t = pi * (i + 0.75) / (n + 0.5);  // asymptotic guess, then Newton in theta
    double p = 0, dp = 0;
    for (int it = 0; it < 100; ++it) {
      legendre_and_theta_derivative(n, t, p, dp);
      const double dt = p / dp;
      t -= dt;
      if (std::abs(dt) < 1e-16 * std::max(1.0, t)) break;
    }
    legendre_and_theta_derivative(n, t, p, dp);
    const double w = 2.0 / (dp * dp);  // 2 / ((1 - x^2) P_n'(x)^2)
    rule.theta[i] = t;
    rule.weights[i] = w;
    rule.theta[n - 1 - i] = pi - t;
    rule.weights[n - 1 - i] = w;
  }
  return rule;
}

}  // namespace rbcflow
