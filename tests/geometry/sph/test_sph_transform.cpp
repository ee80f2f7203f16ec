#include "geometry/sph/sph_transform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <random>
#include <vector>

using namespace rbcflow;

namespace {

SHCoeffs random_coeffs(int order, int components, unsigned seed) {
  SHCoeffs c(order, components);
  std::mt19937 gen(seed);
  std::normal_distribution<double> dist;
  for (Eigen::Index i = 0; i < c.values().size(); ++i) c.values().data()[i] = dist(gen);
  return c;
}

// g(theta) = sin^m(theta) cos^p(theta) as a Laurent polynomial in z = e^{i theta}, so that
// its derivatives come in closed form: g^(a) = sum_k c_k (i k)^a e^{i k theta}.
struct TrigPolynomial {
  int offset = 0;  // coefficient of z^k stored at k + offset
  std::vector<std::complex<double>> c{1.0};

  void multiply(std::complex<double> lo, std::complex<double> hi) {  // by lo/z + hi z
    std::vector<std::complex<double>> r(c.size() + 2, 0.0);
    for (std::size_t i = 0; i < c.size(); ++i) {
      r[i] += lo * c[i];
      r[i + 2] += hi * c[i];
    }
    c = r;
    offset += 1;
  }
  double derivative(int a, double theta) const {
    std::complex<double> s = 0.0;
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double k = double(i) - offset;
      s += c[i] * std::pow(std::complex<double>(0.0, k), a) * std::exp(std::complex<double>(0.0, k * theta));
    }
    return s.real();
  }
};

TrigPolynomial sin_cos_power(int m, int p) {
  TrigPolynomial t;
  const std::complex<double> i(0.0, 1.0);
  for (int q = 0; q < m; ++q) t.multiply(-1.0 / (2.0 * i), 1.0 / (2.0 * i));  // sin
  for (int q = 0; q < p; ++q) t.multiply(0.5, 0.5);                          // cos
  return t;
}

}  // namespace

TEST(SHTransform, RoundTripOfRandomBandLimitedCoefficients) {
  std::printf("  N    max relative round-trip error\n");
  for (int N : {8, 16, 32, 64, 128}) {
    const SHTransform t = SHTransform::gauss(N, 0);
    const SHCoeffs c = random_coeffs(N, 3, 100 + N);
    const SHCoeffs back = t.analyze(t.synthesize(c));
    const double err = (back.values() - c.values()).cwiseAbs().maxCoeff() / c.values().cwiseAbs().maxCoeff();
    std::printf("%4d    %.2e\n", N, err);
    EXPECT_LT(err, 1e-12) << "N = " << N;
  }
}

TEST(SHTransform, GridValuesMatchPointEvaluation) {
  const int N = 12;
  const SHTransform t = SHTransform::gauss(N, 2);
  const SHCoeffs c = random_coeffs(N, 2, 7);
  for (auto [dt, dp] : {std::pair{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}) {
    const Eigen::MatrixXd v = t.synthesize(c, dt, dp);
    for (int p : {0, 5, 77, t.grid().size() - 1}) {
      const int i = p / t.grid().n_phi(), j = p % t.grid().n_phi();
      const Eigen::RowVectorXd e = sh_evaluate(c, t.grid().theta()[i], t.grid().phi(j), dt, dp);
      EXPECT_NEAR((v.row(p) - e).norm(), 0.0, 1e-11 * (1 + e.norm())) << dt << "," << dp;
    }
  }
}

TEST(SHTransform, UniformGridWithPolesMatchesPointEvaluation) {
  const int N = 10;
  const SHTransform t(N, SphGrid::uniform(2 * N + 1, 2 * N), 1);
  const SHCoeffs c = random_coeffs(N, 1, 3);
  const Eigen::MatrixXd v = t.synthesize(c);
  for (int p = 0; p < t.grid().size(); p += 7) {
    const int i = p / t.grid().n_phi(), j = p % t.grid().n_phi();
    EXPECT_NEAR(v(p, 0), sh_evaluate(c, t.grid().theta()[i], t.grid().phi(j))(0), 1e-12);
  }
  // A function is single-valued at a pole: every longitude gives the same value.
  for (int j = 1; j < t.grid().n_phi(); ++j) EXPECT_NEAR(v(j, 0), v(0, 0), 1e-12);
}

TEST(SHTransform, DerivativesOfBandLimitedFunctionsMatchClosedForms) {
  // f = sum_terms sin^m(theta) cos^p(theta) cos(m phi + phase): each term is a polynomial of
  // degree m + p in the unit vector, hence band-limited to degree < N when m + p < N.
  const int N = 16;
  const SHTransform t = SHTransform::gauss(N, 4);
  struct Term { int m, p; double phase, amp; };
  const std::vector<Term> terms = {{0, 3, 0.0, 1.0}, {1, 6, 0.3, -0.7}, {3, 4, 1.1, 0.5},
                                   {5, 10, -0.4, 0.9}, {14, 1, 0.2, 0.05}, {15, 0, 0.7, 0.02}};
  const SphGrid& g = t.grid();
  auto exact = [&](int a, int b, double theta, double phi) {
    double s = 0.0;
    for (const Term& q : terms) {
      // d^b/dphi^b cos(m phi + phase) = m^b cos(m phi + phase + b pi / 2)
      const double angular = std::pow(q.m, b) * std::cos(q.m * phi + q.phase + b * std::numbers::pi / 2);
      s += q.amp * sin_cos_power(q.m, q.p).derivative(a, theta) * angular;
    }
    return s;
  };
  Eigen::MatrixXd f(g.size(), 1);
  for (int p = 0; p < g.size(); ++p) f(p, 0) = exact(0, 0, g.theta()[p / g.n_phi()], g.phi(p % g.n_phi()));
  const SHCoeffs c = t.analyze(f);
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; a + b <= 4; ++b) {
      const Eigen::MatrixXd d = t.synthesize(c, a, b);
      double err = 0.0, scale = 0.0;
      for (int p = 0; p < g.size(); ++p) {
        const double e = exact(a, b, g.theta()[p / g.n_phi()], g.phi(p % g.n_phi()));
        err = std::max(err, std::abs(d(p, 0) - e));
        scale = std::max(scale, std::abs(e));
      }
      EXPECT_LT(err / scale, 1e-10) << "d^" << a << "/dtheta d^" << b << "/dphi";
    }
  }
}

TEST(SHTransform, ResamplingToHigherOrderAndBackIsExact) {
  for (auto [N, M] : {std::pair{8, 24}, {16, 48}, {16, 32}, {32, 64}}) {
    const SHCoeffs c = random_coeffs(N, 3, N + M);
    const SHTransform tm = SHTransform::gauss(M, 0);
    // Synthesise the order-N field on the M x 2M grid, analyse at order M, truncate to N.
    const SHCoeffs up = tm.analyze(tm.synthesize(c));
    EXPECT_LT((up.resampled(N).values() - c.values()).cwiseAbs().maxCoeff(), 1e-13);
    // The modes n >= N of the zero-padded field stay zero.
    EXPECT_LT((up.values() - c.resampled(M).values()).cwiseAbs().maxCoeff(), 1e-13);
    // Direct truncating analysis (the de-aliasing filter) gives the same.
    EXPECT_LT((tm.analyze(tm.synthesize(c.resampled(M)), N).values() - c.values()).cwiseAbs().maxCoeff(), 1e-13);
  }
}

// The jet (value and derivatives to second order from one Legendre table) equals the separate
// point evaluations.
TEST(SHTransform, JetMatchesPointEvaluations) {
  const SHCoeffs c = random_coeffs(12, 3, 7);
  for (auto [t, ph] : {std::pair{0.01, 0.2}, {1.1, 3.0}, {2.9, 6.1}}) {
    const SHJet j = sh_evaluate_jet(c, t, ph);
    const std::pair<const Eigen::Vector3d*, std::pair<int, int>> parts[] = {
        {&j.x, {0, 0}}, {&j.x_t, {1, 0}}, {&j.x_p, {0, 1}}, {&j.x_tt, {2, 0}}, {&j.x_tp, {1, 1}}, {&j.x_pp, {0, 2}}};
    for (const auto& [value, d] : parts) {
      const Eigen::Vector3d expected = sh_evaluate(c, t, ph, d.first, d.second).transpose();
      EXPECT_LT((*value - expected).norm(), 1e-12 * (1.0 + expected.norm()))
          << "d/dtheta^" << d.first << " d/dphi^" << d.second << " at " << t << ", " << ph;
    }
  }
}

TEST(SHCoeffs, SpectrumSumsSquaresPerDegree) {
  SHCoeffs c(4, 3);
  c.a(2, 1, 0) = 3.0;
  c.b(2, 2, 2) = 4.0;
  c.a(3, 0, 1) = 1.0;
  const Eigen::VectorXd e = c.spectrum();
  EXPECT_DOUBLE_EQ(e[0], 0.0);
  EXPECT_DOUBLE_EQ(e[2], 25.0);
  EXPECT_DOUBLE_EQ(e[3], 1.0);
}

TEST(SHTransform, RejectsTooFewLongitudesAndMismatchedFields) {
  EXPECT_THROW(SHTransform(8, SphGrid::gauss(8, 10), 0), std::invalid_argument);
  const SHTransform t = SHTransform::gauss(8, 1);
  EXPECT_THROW(t.analyze(Eigen::MatrixXd::Zero(5, 3)), std::invalid_argument);
  EXPECT_THROW(t.synthesize(SHCoeffs(9, 1)), std::invalid_argument);
  EXPECT_THROW(t.synthesize(SHCoeffs(8, 1), 2, 0), std::invalid_argument);
}
