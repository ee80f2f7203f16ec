#include "libsolver/stepper/gmres.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

using namespace rbcflow;

TEST(Gmres, SolvesANonsymmetricSystemWithRestarts) {
  const int n = 120;
  std::mt19937 gen(1);
  std::normal_distribution<double> nd;
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) M(i, j) += 0.3 * nd(gen) / std::sqrt(double(n));
  }
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = nd(gen);
  Eigen::VectorXd x;
  const GmresResult r = gmres([&](const Eigen::VectorXd& v) { return Eigen::VectorXd(M * v); }, b, x, 1e-10, 500, 20);
  EXPECT_TRUE(r.converged);
  EXPECT_LT((M * x - b).norm() / b.norm(), 1e-9);
  EXPECT_LT((x - M.lu().solve(b)).norm() / x.norm(), 1e-8);
}

TEST(Gmres, ReportsNonConvergence) {
  const int n = 50;
  Eigen::VectorXd d = Eigen::VectorXd::LinSpaced(n, 1e-6, 1.0);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(n), x;
  const GmresResult r = gmres([&](const Eigen::VectorXd& v) { return Eigen::VectorXd(d.cwiseProduct(v)); }, b, x, 1e-14, 5, 5);
  EXPECT_FALSE(r.converged);
  EXPECT_EQ(r.iterations, 5);
}
