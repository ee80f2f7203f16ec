#include <gtest/gtest.h>

#include "libsolver/spme/ewald_direct.h"
#include "libsolver/spme/real_space_sum.h"
#include "test_points.h"

using namespace rbcflow;
using test::random_points;
using test::random_unit_vectors;
using test::random_vectors;

// The cell-list sums equal the brute-force real-space sums of EwaldDirect for the same cutoff,
// with a cutoff below and one above half the box, and with targets equal to the sources.
TEST(RealSpaceSum, MatchesBruteForce) {
  const Eigen::Vector3d L(1.0, 0.7, 1.2);
  const PeriodicBox box(L);
  const double xi = 4.0;
  const PointField xs = random_points(120, L, 1), xt = random_points(50, L, 2);
  const PointField f = random_vectors(120, 3), q = random_vectors(120, 4),
                   n = random_unit_vectors(120, 5);
  for (double cutoff : {0.3, 0.85}) {
    const EwaldDirect direct(box, xi, cutoff, 1.0);
    for (const PointField* targets : {&xt, &xs}) {
      const NeighborList pairs(box, cutoff, xs, *targets);
      const PointField s = real_space_single_layer(pairs, xi, f);
      const PointField s_ref = direct.real_single_layer(xs, f, *targets);
      EXPECT_LT((s - s_ref).norm(), 1e-12 * s_ref.norm());
      const PointField d = real_space_double_layer(pairs, xi, q, n);
      const PointField d_ref = direct.real_double_layer(xs, q, n, *targets);
      EXPECT_LT((d - d_ref).norm(), 1e-12 * d_ref.norm());
    }
  }
}

// Kept pair coefficients: the product that fills them and every later product (other
// densities, the same list) equal the brute-force sums.
TEST(RealSpaceSum, KeptCoefficientsGiveTheSameSums) {
  const Eigen::Vector3d L(1.0, 0.7, 1.2);
  const PeriodicBox box(L);
  const double xi = 4.0, cutoff = 0.6;
  const PointField xs = random_points(150, L, 11), xt = random_points(60, L, 12);
  const EwaldDirect direct(box, xi, cutoff, 1.0);
  const NeighborList pairs(box, cutoff, xs, xt);
  std::vector<double> single, double_;
  for (unsigned seed : {21u, 22u, 23u}) {
    const PointField f = random_vectors(150, seed), q = random_vectors(150, seed + 10),
                     n = random_unit_vectors(150, seed + 20);
    const PointField s_ref = direct.real_single_layer(xs, f, xt);
    EXPECT_LT((real_space_single_layer(pairs, xi, f, &single) - s_ref).norm(), 1e-12 * s_ref.norm());
    const PointField d_ref = direct.real_double_layer(xs, q, n, xt);
    EXPECT_LT((real_space_double_layer(pairs, xi, q, n, &double_) - d_ref).norm(), 1e-12 * d_ref.norm());
    EXPECT_EQ(single.size(), 2 * static_cast<std::size_t>(pairs.n_pairs()));
    EXPECT_EQ(double_.size(), 2 * static_cast<std::size_t>(pairs.n_pairs()));
  }
}

TEST(RealSpaceSum, RejectsMismatchedDensities) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  const PointField x = random_points(10, Eigen::Vector3d::Ones(), 1);
  const NeighborList pairs(box, 0.3, x, x);
  EXPECT_THROW(real_space_single_layer(pairs, 5.0, random_vectors(9, 1)), std::invalid_argument);
  EXPECT_THROW(real_space_double_layer(pairs, 5.0, random_vectors(10, 1), random_vectors(8, 2)),
               std::invalid_argument);
}
