#include "ewald_error_estimates.h"

#include <cmath>
#include <numbers>

#include "geometry/sph/gauss_legendre.h"

namespace rbcflow {
namespace {

constexpr double pi = std::numbers::pi;

// Calibration of the grid-error model: measured / modelled RMS error of the smooth part against
// the direct Fourier sum, 300 random sources, xi L = 4 .. 16, K = 16 .. 64, p = 4 .. 10: 1.8 to
// 2.4 for even p (the choice), 1.0 to 1.5 for odd p.
constexpr double kGridCalibrationStokeslet = 2.0;
constexpr double kGridCalibrationStresslet = 2.2;

// E1(x) = integral_x^inf e^{-t}/t dt.
double exponential_integral_e1(double x) { return -std::expint(-x); }

// g(k1) = integral dk2 dk3 |K^F(k)|^2 = pi integral_{k1^2}^inf F(s) ds, s = |k|^2, with the
// squared kernel averaged over random source directions:
//   stokeslet F = (2/3) (8 pi)^2 (1/s + c)^2 e^{-2 c s},
//   stresslet F = (7/9) (8 pi)^2 (1/s + c)^2 s e^{-2 c s},   c = 1/(4 xi^2).
double transverse_kernel_power(EwaldKernel kernel, double xi, double k1) {
  const double c = 0.25 / (xi * xi), a = 2.0 * c, s0 = k1 * k1;
  const double e = std::exp(-a * s0), e1 = exponential_integral_e1(a * s0);
  const double i_m2 = e / s0 - a * e1;  // integral e^{-as}/s^2
  const double i_m1 = e1;               // integral e^{-as}/s
  const double i_0 = e / a;             // integral e^{-as}
  const double i_1 = e * (s0 / a + 1.0 / (a * a));
  const double k0 = 64.0 * pi * pi;
  if (kernel == EwaldKernel::stokeslet)
    return pi * (2.0 / 3.0) * k0 * (i_m2 + 2.0 * c * i_m1 + c * c * i_0);
  return pi * (7.0 / 9.0) * k0 * (i_m1 + 2.0 * c * i_0 + c * c * i_1);
}

// Squared aliasing of B-spline interpolation of order p at theta = k h in (-pi, pi), spreading
// and interpolation together.
double aliasing_power(double theta, int order) {
  double sum = 0.0;
  for (int m = 1; m <= 3; ++m) {
    sum += std::pow(theta / (theta + 2.0 * pi * m), 2 * order) +
           std::pow(theta / (theta - 2.0 * pi * m), 2 * order);
  }
  return 2.0 * sum;
}

const GaussLegendreRule& quadrature() {
  static const GaussLegendreRule rule = gauss_legendre(48);
  return rule;
}

// integral over k1 of the error power of one direction with spacing h:
//   2 integral_0^{pi/h} aliasing(k1 h) g(k1) dk1 + 2 integral_{pi/h}^inf g(k1) dk1.
double direction_error_power(EwaldKernel kernel, double xi, double h, int order) {
  const GaussLegendreRule& q = quadrature();
  const double k_nyquist = pi / h;
  // The tail decays like exp(-2 c k^2): on the scale 1 / (4 c k_N + sqrt(2 c)).
  const double c = 0.25 / (xi * xi);
  const double tail_scale = 1.0 / (4.0 * c * k_nyquist + std::sqrt(2.0 * c));
  const double tail_length = 40.0 * tail_scale;
  double inner = 0.0, tail = 0.0;
  for (int i = 0; i < q.theta.size(); ++i) {
    const double x = std::cos(q.theta[i]), w = q.weights[i];  // node in (-1, 1)
    const double k_in = 0.5 * k_nyquist * (1.0 + x);
    inner += 0.5 * k_nyquist * w * aliasing_power(k_in * h, order) *
             transverse_kernel_power(kernel, xi, k_in);
    const double k_out = k_nyquist + 0.5 * tail_length * (1.0 + x);
    tail += 0.5 * tail_length * w * transverse_kernel_power(kernel, xi, k_out);
  }
  return 2.0 * (inner + tail);
}

// Parseval: mean |error|^2 = (Q / V) (2 pi)^-3 integral |K^F|^2 (aliasing) d^3k, normalised
// by sqrt(Q)/ell or sqrt(Q_T)/ell^2 (see header).
double normalised_rms(EwaldKernel kernel, const PeriodicBox& box, double power) {
  const double calibration =
      kernel == EwaldKernel::stokeslet ? kGridCalibrationStokeslet : kGridCalibrationStresslet;
  const double ell = std::cbrt(box.volume());
  const double rms = calibration * std::sqrt(power / (8.0 * pi * pi * pi * box.volume()));
  return rms * (kernel == EwaldKernel::stokeslet ? ell : ell * ell);
}

}  // namespace

const char* to_string(EwaldKernel kernel) {
  return kernel == EwaldKernel::stokeslet ? "stokeslet (single layer)" : "stresslet (double layer)";
}

double real_space_error(EwaldKernel kernel, const PeriodicBox& box, double xi, double cutoff) {
  const double V = box.volume(), decay = std::exp(-xi * xi * cutoff * cutoff);
  const double e = kernel == EwaldKernel::stokeslet
                       ? std::sqrt(8.0 * cutoff / (3.0 * V)) * decay
                       : 3.53 * xi * xi * std::pow(cutoff, 1.5) * std::sqrt(1.0 / V) * decay;
  const double ell = std::cbrt(V);
  return e * (kernel == EwaldKernel::stokeslet ? ell : ell * ell);
}

double spme_grid_error(EwaldKernel kernel, const PeriodicBox& box, double xi,
                       const std::array<int, 3>& grid, int order) {
  double power = 0.0;
  for (int d = 0; d < 3; ++d)
    power += direction_error_power(kernel, xi, box.length(d) / grid[d], order);
  return normalised_rms(kernel, box, power);
}

double spme_grid_error(EwaldKernel kernel, const PeriodicBox& box, double xi, double spacing,
                       int order) {
  return normalised_rms(kernel, box, 3.0 * direction_error_power(kernel, xi, spacing, order));
}

}  // namespace rbcflow
