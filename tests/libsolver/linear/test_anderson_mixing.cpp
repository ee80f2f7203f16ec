// Anderson mixing (libsolver/linear/anderson_mixing.h) on affine maps F(x) = A x + c, whose
// fixed point solves (I - A) x = c exactly (a dense LU solve is the reference):
// - with an unbounded history its iterates are Walker & Ni's (SIAM J. Numer. Anal. 49, 2011,
//   theorem 2.2): x_{k+1} = F(x_k^GMRES), GMRES's k-th iterate on (I - A) x = c from the same
//   start (preconditioned_gmres.h);
// - with depth 0 it is the plain iteration, to the bit;
// - with depth 5 it reaches the fixed point in a fraction of the plain iteration's sweeps when
//   a few slow modes set the plain iteration's rate (as in the stepper's start sweeps, whose
//   change falls by a steady ~0.5 a sweep).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "libsolver/linear/anderson_mixing.h"
#include "libsolver/linear/preconditioned_gmres.h"

using namespace rbcflow;

namespace {

constexpr int kN = 80;

// A = Q diag(mu) Q^T + 0.05 S / sqrt(n): `slow` eigenvalues of the symmetric part spread over
// [rho / 2, rho], the others over [-rho, rho] (all of them when slow = 0); a mildly non-normal
// perturbation; c random. Iterates are n x 2 matrices (the
// mixing treats any shape as a vector), stacked column-wise for the dense algebra.
struct AffineMap {
  Eigen::MatrixXd A;
  Eigen::VectorXd c;
  AffineMap(double rho, int slow) {
    std::mt19937 rng(11);
    std::normal_distribution<double> g;
    Eigen::MatrixXd R(2 * kN, 2 * kN), S(2 * kN, 2 * kN);
    for (int i = 0; i < 2 * kN; ++i)
      for (int j = 0; j < 2 * kN; ++j) R(i, j) = g(rng), S(i, j) = g(rng) / std::sqrt(2.0 * kN);
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(R).householderQ();
    Eigen::VectorXd mu(2 * kN);
    for (int i = 0; i < 2 * kN; ++i) mu[i] = rho * (2.0 * i / (2 * kN - 1) - 1.0);
    if (slow > 0) {
      mu *= 0.05;
      for (int i = 0; i < slow; ++i) mu[i] = rho * (0.5 + 0.5 * i / std::max(1, slow - 1));
    }
    A = Q * mu.asDiagonal() * Q.transpose() + 0.05 * S;
    c = Eigen::VectorXd::NullaryExpr(2 * kN, [&] { return g(rng); });
  }
  Eigen::VectorXd apply(const Eigen::VectorXd& x) const { return A * x + c; }
  Eigen::MatrixXd apply(const Eigen::MatrixXd& x) const {
    const Eigen::VectorXd y = apply(Eigen::VectorXd(x.reshaped()));
    return y.reshaped(kN, 2);
  }
  Eigen::VectorXd fixed_point() const {
    return (Eigen::MatrixXd::Identity(2 * kN, 2 * kN) - A).partialPivLu().solve(c);
  }
};

double relative_change(const Eigen::MatrixXd& x, const Eigen::MatrixXd& fx) { return (fx - x).norm() / fx.norm(); }

// Sweeps x = next(x, F(x)) from x = 0 until |F(x) - x| <= tolerance |F(x)|.
int sweeps_to(const AffineMap& F, int depth, double tolerance, Eigen::MatrixXd& x) {
  AndersonMixing mixing(depth);
  x = Eigen::MatrixXd::Zero(kN, 2);
  for (int sweep = 1; sweep <= 5000; ++sweep) {
    const Eigen::MatrixXd fx = F.apply(x);
    if (relative_change(x, fx) <= tolerance) return sweep;
    x = mixing.next(x, fx);
  }
  return -1;
}

}  // namespace

TEST(AndersonMixing, UnboundedHistoryGivesTheImagesOfGmresIterates) {
  const AffineMap F(0.9, 0);
  AndersonMixing mixing(1000);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(kN, 2);
  const Eigen::VectorXd b = F.c;
  const auto I_minus_A = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(v - F.A * v); };
  double worst = 0;
  for (int k = 0; k <= 12; ++k) {
    x = mixing.next(x, F.apply(x));  // x_{k+1}
    Eigen::VectorXd xg = Eigen::VectorXd::Zero(2 * kN);
    if (k > 0) gmres(I_minus_A, b, xg, 1e-30, k, 1000);
    const Eigen::VectorXd expected = F.apply(xg);
    const double diff = (Eigen::VectorXd(x.reshaped()) - expected).norm() / expected.norm();
    std::printf("k = %2d: |x_{k+1} - F(x_k^GMRES)| / |F(x_k^GMRES)| = %.2e\n", k, diff);
    worst = std::max(worst, diff);
  }
  // Both sides are exact in exact arithmetic; the mixing's normal equations square the
  // condition of dG, whose columns decay like the residuals (0.9^k of the first here).
  EXPECT_LT(worst, 1e-9);
}

TEST(AndersonMixing, DepthZeroIsThePlainIteration) {
  const AffineMap F(0.9, 0);
  AndersonMixing mixing(0);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(kN, 2), plain = x;
  for (int k = 0; k < 10; ++k) {
    x = mixing.next(x, F.apply(x));
    plain = F.apply(plain);
    ASSERT_EQ(x, plain) << "sweep " << k;
  }
  EXPECT_EQ(mixing.history(), 0);
}

TEST(AndersonMixing, ReachesTheFixedPointInAFractionOfThePlainSweeps) {
  for (const double rho : {0.5, 0.95}) {
    const AffineMap F(rho, 4);
    const Eigen::VectorXd exact = F.fixed_point();
    Eigen::MatrixXd plain, mixed;
    const int n_plain = sweeps_to(F, 0, 1e-10, plain), n_mixed = sweeps_to(F, 5, 1e-10, mixed);
    const double err_plain = (Eigen::VectorXd(plain.reshaped()) - exact).norm() / exact.norm();
    const double err_mixed = (Eigen::VectorXd(mixed.reshaped()) - exact).norm() / exact.norm();
    std::printf("rho %.2f: plain %d sweeps (error %.1e), Anderson(5) %d sweeps (error %.1e)\n", rho, n_plain,
                err_plain, n_mixed, err_mixed);
    ASSERT_GT(n_plain, 0);
    ASSERT_GT(n_mixed, 0);
    // |x - x*| <= |(I - A)^{-1}| |F(x) - x|: 1e-10 times a resolvent norm of O(1 / (1 - rho)).
    EXPECT_LT(err_mixed, 1e-10 / (1 - rho) * 10);
    // Plain sweeps go like log(tolerance) / log(rho) (measured 27 and 353); Anderson's follow
    // the fast modes once it has spanned the 4 slow ones (measured 14 and 21).
    EXPECT_LT(3 * n_mixed, 2 * n_plain);
    if (rho > 0.9) {
      EXPECT_LT(10 * n_mixed, n_plain);
    }
  }
}

// The next iterate is a combination of the F(x_i), so the mixing carries their images under a
// linear map L along: L x_{k+1} to rounding, at every sweep, with the history full and cut.
TEST(AndersonMixing, CarriesTheImagesOfItsIterates) {
  const AffineMap F(0.9, 4);
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  const Eigen::MatrixXd L = Eigen::MatrixXd::NullaryExpr(2 * kN, 2 * kN, [&] { return g(rng); });
  const auto image_of = [&](const Eigen::MatrixXd& x) {
    return Eigen::MatrixXd((L * Eigen::VectorXd(x.reshaped())).reshaped(kN, 2));
  };
  AndersonMixing mixing(3), plain_mixing(3);
  Eigen::MatrixXd x = Eigen::MatrixXd::Zero(kN, 2), y = x;
  for (int k = 0; k < 12; ++k) {
    const Eigen::MatrixXd f = F.apply(x);
    Eigen::MatrixXd image = image_of(f);
    x = mixing.next(x, f, image, image);  // the image given and returned in one matrix
    y = plain_mixing.next(y, F.apply(y));
    EXPECT_LT((image - image_of(x)).norm(), 1e-12 * image.norm()) << "sweep " << k;
    EXPECT_EQ(x, y) << "sweep " << k;  // the images change nothing else
  }
  Eigen::MatrixXd image;
  EXPECT_THROW(plain_mixing.next(y, F.apply(y), image_of(y), image), std::logic_error);
}
