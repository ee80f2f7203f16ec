// GMRES with Krylov recycling (libsolver/linear/preconditioned_gmres.h) on a dense
// non-symmetric matrix with a cluster of small eigenvalues (the slow modes recycling is for):
// the recycled space satisfies its defining relations to rounding, a solve with it reaches
// the same solution to the tolerance, and later right-hand sides take fewer iterations.
// Measured: GMRES(100) to 1e-8 takes 182-190 iterations for random right-hand sides, 86-87 with
// the 100 directions of one earlier solve; a halving is asserted.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>

#include "libsolver/linear/preconditioned_gmres.h"

using namespace rbcflow;

namespace {

constexpr int kN = 300;

// A = Q diag(lambda) Q^T + 0.02 S (S a random non-symmetric matrix): eigenvalues in [1, 10]
// apart from 20 in 0.01..0.05. M^{-1} = diag(A)^{-1}.
struct Problem {
  Eigen::MatrixXd A;
  Eigen::VectorXd d;
  Problem() {
    std::mt19937 rng(7);
    std::normal_distribution<double> g;
    Eigen::MatrixXd R(kN, kN), S(kN, kN);
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) R(i, j) = g(rng), S(i, j) = g(rng) / std::sqrt(double(kN));
    const Eigen::MatrixXd Q = Eigen::HouseholderQR<Eigen::MatrixXd>(R).householderQ();
    Eigen::VectorXd lambda(kN);
    for (int i = 0; i < kN; ++i) lambda[i] = i < 20 ? 1e-2 * (1 + 0.2 * i) : 1 + 9.0 * (i - 20) / (kN - 21);
    A = Q * lambda.asDiagonal() * Q.transpose() + 0.02 * S;
    d = A.diagonal();
  }
  Eigen::VectorXd apply(const Eigen::VectorXd& x) const { return A * x; }
  Eigen::VectorXd precondition(const Eigen::VectorXd& r) const { return r.cwiseQuotient(d); }
};

Eigen::VectorXd rhs(int seed) {
  std::mt19937 rng(100 + seed);
  std::normal_distribution<double> g;
  Eigen::VectorXd b(kN);
  for (int i = 0; i < kN; ++i) b[i] = g(rng);
  return b;
}

}  // namespace

TEST(PreconditionedGmres, RecyclingKeepsTheSolutionAndCutsIterations) {
  const Problem P;
  auto A = [&](const Eigen::VectorXd& x) { return P.apply(x); };
  auto M = [&](const Eigen::VectorXd& r) { return P.precondition(r); };
  const double tol = 1e-8;

  RecycledSpace space;
  space.capacity = 100;
  space.growing = true;
  Eigen::VectorXd x0;
  const GmresReport seed = preconditioned_gmres(A, M, rhs(0), x0, tol, 2000, 100, &space);
  ASSERT_TRUE(seed.converged);
  space.growing = false;
  ASSERT_EQ(space.size(), 100);
  // A M^{-1} U = C and C^T C = I.
  Eigen::MatrixXd AMU(kN, space.size());
  for (int j = 0; j < space.size(); ++j) AMU.col(j) = A(M(space.U.col(j)));
  EXPECT_LT((AMU - space.C).norm() / space.C.norm(), 1e-10);
  EXPECT_LT((space.C.transpose() * space.C - Eigen::MatrixXd::Identity(space.size(), space.size())).norm(), 1e-10);

  for (int k = 1; k <= 3; ++k) {
    const Eigen::VectorXd b = rhs(k);
    Eigen::VectorXd plain, recycled;
    const GmresReport p = preconditioned_gmres(A, M, b, plain, tol, 2000, 100);
    const GmresReport r = preconditioned_gmres(A, M, b, recycled, tol, 2000, 100, &space);
    ASSERT_TRUE(p.converged);
    ASSERT_TRUE(r.converged);
    EXPECT_LE((b - A(recycled)).norm(), tol * b.norm());  // the true residual
    // Both within tol of the same solution: |x - y| <= |A^{-1}| 2 tol |b| (|A^{-1}| ~ 1/1e-2).
    const Eigen::VectorXd exact = P.A.partialPivLu().solve(b);
    EXPECT_LT((recycled - exact).norm(), 2e2 * tol * b.norm());
    EXPECT_LT((plain - exact).norm(), 2e2 * tol * b.norm());
    std::printf("rhs %d: %d iterations plain, %d with %d recycled directions\n", k, p.iterations, r.iterations,
                space.size());
    EXPECT_LT(r.iterations, p.iterations / 2) << "rhs " << k;
  }
}

TEST(PreconditionedGmres, AnEmptySpaceChangesNothing) {
  const Problem P;
  auto A = [&](const Eigen::VectorXd& x) { return P.apply(x); };
  auto M = [&](const Eigen::VectorXd& r) { return P.precondition(r); };
  RecycledSpace empty;
  Eigen::VectorXd a, b;
  const GmresReport ra = preconditioned_gmres(A, M, rhs(1), a, 1e-8, 2000, 30);
  const GmresReport rb = preconditioned_gmres(A, M, rhs(1), b, 1e-8, 2000, 30, &empty);
  EXPECT_EQ(ra.iterations, rb.iterations);
  EXPECT_EQ((a - b).norm(), 0.0);
}

namespace {

// M = I + 0.3 R / sqrt(n), R standard normal (eigenvalues in a disc of radius ~0.3 about 1),
// and a standard normal b.
struct NearIdentitySystem {
  Eigen::MatrixXd M;
  Eigen::VectorXd b;
};
NearIdentitySystem near_identity_system(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::normal_distribution<double> nd;
  NearIdentitySystem s{Eigen::MatrixXd::Identity(n, n), Eigen::VectorXd(n)};
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) s.M(i, j) += 0.3 * nd(gen) / std::sqrt(double(n));
  }
  for (int i = 0; i < n; ++i) s.b[i] = nd(gen);
  return s;
}

}  // namespace

// Without a preconditioner (the cells' solve (10)).
TEST(PlainGmres, SolvesANonsymmetricSystemWithRestarts) {
  const auto [M, b] = near_identity_system(120, 1);
  Eigen::VectorXd x;
  const GmresReport r = gmres([&](const Eigen::VectorXd& v) { return Eigen::VectorXd(M * v); }, b, x, 1e-10, 500, 20);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((M * x - b).norm() / b.norm(), 1e-9);
  EXPECT_LT((x - M.lu().solve(b)).norm() / x.norm(), 1e-8);
}

// A converged solve applies A once for the initial residual and once per iteration: the
// residual it reports is the Arnoldi one, which is the true one (checked here to 1e-12 of |b|).
TEST(PlainGmres, EndsWithoutRecomputingTheResidual) {
  const auto [M, b] = near_identity_system(120, 3);
  for (const int restart : {60, 7}) {
    int products = 0;
    Eigen::VectorXd x;
    const GmresReport r = gmres(
        [&](const Eigen::VectorXd& v) {
          ++products;
          return Eigen::VectorXd(M * v);
        },
        b, x, 1e-8, 500, restart);
    ASSERT_TRUE(r.converged);
    const int cycles = (r.iterations + restart - 1) / restart;  // each starts from b - A x
    EXPECT_EQ(products, r.iterations + cycles) << "restart " << restart;
    const double true_residual = (b - M * x).norm() / b.norm();
    EXPECT_LE(true_residual, 1e-8);
    EXPECT_NEAR(r.relative_residual, true_residual, 1e-12);
  }
}

// The image A x: returned for the solution from the Arnoldi relation (no product), and taken
// on entry for the initial guess instead of the first product; the solve from a known image is
// the solve from a computed one. Preconditioned and recycled too (the wall's form).
TEST(PlainGmres, ReturnsAndTakesTheImageOfItsIterate) {
  const auto [M, b] = near_identity_system(120, 5);
  for (const int restart : {60, 7}) {
    int products = 0;
    const auto A = [&](const Eigen::VectorXd& v) {
      ++products;
      return Eigen::VectorXd(M * v);
    };
    Eigen::VectorXd x, image;
    const GmresReport first = gmres(A, b, x, 1e-6, 500, restart, &image);
    ASSERT_TRUE(first.converged);
    EXPECT_LT((image - M * x).norm(), 1e-12 * b.norm()) << "restart " << restart;
    // A second right-hand side from x, with and without the image.
    const Eigen::VectorXd b2 = b + 0.1 * Eigen::VectorXd::Ones(b.size());
    Eigen::VectorXd with = x, without = x, image2 = image;
    products = 0;
    const GmresReport r_with = gmres(A, b2, with, 1e-8, 500, restart, &image2);
    const int products_with = products;
    products = 0;
    const GmresReport r_without = gmres(A, b2, without, 1e-8, 500, restart);
    ASSERT_TRUE(r_with.converged && r_without.converged);
    EXPECT_EQ(r_with.iterations, r_without.iterations);
    EXPECT_EQ(products_with, products - 1) << "restart " << restart;
    EXPECT_LT((with - without).norm(), 1e-12 * without.norm());
    EXPECT_LT((b2 - M * with).norm(), 1e-8 * b2.norm());
    EXPECT_LT((image2 - M * with).norm(), 1e-12 * b2.norm());
  }
  // Preconditioned (a diagonal M^{-1}) and with a recycled space grown by the first solve.
  const Eigen::VectorXd d = M.diagonal().cwiseInverse();
  const auto P = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(d.cwiseProduct(v)); };
  const auto A = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(M * v); };
  RecycledSpace space;
  space.capacity = 10;
  space.growing = true;
  Eigen::VectorXd x, image;
  ASSERT_TRUE(preconditioned_gmres(A, P, b, x, 1e-6, 500, 60, &space, &image).converged);
  EXPECT_GT(space.size(), 0);
  EXPECT_LT((image - M * x).norm(), 1e-12 * b.norm());
  space.growing = false;
  const Eigen::VectorXd b2 = 2 * b;
  ASSERT_TRUE(preconditioned_gmres(A, P, b2, x, 1e-6, 500, 60, &space, &image).converged);
  EXPECT_LT((image - M * x).norm(), 1e-12 * b2.norm());
  EXPECT_LT((b2 - M * x).norm(), 1e-6 * b2.norm());
}

TEST(PlainGmres, ReportsNonConvergence) {
  const int n = 50;
  Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, 1e-6, 1.0);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(n), x;
  const GmresReport r = gmres([&](const Eigen::VectorXd& v) { return Eigen::VectorXd(d.cwiseProduct(v)); }, b, x, 1e-14, 5, 5);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 5);
}
