#include <gtest/gtest.h>

#include "libsolver/kernels/ewald_kernels.h"
#include "tests/libsolver/spme/ewald_direct.h"
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

// PairShares: a shared pair counts with weight 1 - share at its nearest image (other images in
// the cutoff keep weight 1), the shares of a source named twice add, and kept coefficients
// carry the weights to later products. Reference: the unweighted sum minus share times the
// pair's term from the kernels of ewald_kernels.h at the nearest image.
TEST(RealSpaceSum, SharedPairsCountWithWeightOneMinusShare) {
  const Eigen::Vector3d L(1.0, 0.7, 1.2);
  const PeriodicBox box(L);
  const double xi = 4.0;
  const PointField xs = random_points(120, L, 31), xt = random_points(50, L, 32);
  for (double cutoff : {0.3, 0.85}) {  // below and above half the shortest side (0.35)
    const NeighborList pairs(box, cutoff, xs, xt);
    const double radius = pair_share_radius(box, cutoff);
    std::vector<std::vector<std::pair<int, double>>> by_target(xt.rows());
    for (int t = 0; t < xt.rows(); ++t) {
      for (int s = t % 3; s < xs.rows(); s += 3) {
        Eigen::Vector3d r = (xs.row(s) - xt.row(t)).transpose();
        r -= (L.array() * (r.array() / L.array()).round()).matrix();
        if (r.norm() >= radius) continue;
        // Shares in sixteenths and thirty-seconds: exact in the single precision PairShares keeps.
        const double share = 0.125 + 0.75 * ((s * 7 + t) % 8) / 8.0;
        by_target[t].push_back({s, share});
        if (by_target[t].size() == 1) by_target[t].push_back({s, 0.0625});  // named twice: 0.0625 more
      }
    }
    // Each target's shares in two segments, as the corrections of two cells leave them: all but
    // the last with the sources as nodes, the last numbered from source -1 (node s + 1).
    PairShares shares;
    std::size_t entries = 0;
    for (const auto& list : by_target) entries += list.size();
    shares.held.reserve(entries);
    shares.offsets.push_back(0);
    for (int t = 0; t < xt.rows(); ++t) {
      const auto& list = by_target[t];
      const std::size_t start = shares.held.size();
      for (std::size_t e = 0; e < list.size(); ++e) {
        const bool last = e + 1 == list.size();
        shares.held.push_back({last ? list[e].first + 1 : list[e].first, static_cast<float>(list[e].second)});
      }
      if (list.size() > 1)
        shares.segments.push_back({shares.held.data() + start, static_cast<std::int32_t>(list.size() - 1), 0});
      if (!list.empty()) shares.segments.push_back({shares.held.data() + start + list.size() - 1, 1, -1});
      shares.offsets.push_back(static_cast<std::int64_t>(shares.segments.size()));
    }
    ASSERT_GT(entries, 100u);
    std::vector<double> single, double_;
    for (unsigned seed : {41u, 42u}) {  // the first fills the kept coefficients, the second reads them
      const PointField f = random_vectors(120, seed), q = random_vectors(120, seed + 10),
                       n = random_unit_vectors(120, seed + 20);
      PointField s_ref = real_space_single_layer(pairs, xi, f), d_ref = real_space_double_layer(pairs, xi, q, n);
      for (int t = 0; t < xt.rows(); ++t) {
        for (const auto& [s, share] : by_target[t]) {
          Eigen::Vector3d r = (xs.row(s) - xt.row(t)).transpose();
          r -= (L.array() * (r.array() / L.array()).round()).matrix();
          s_ref.row(t) -= share * ewald_real_stokeslet_apply(r, xi, f.row(s).transpose()).transpose();
          d_ref.row(t) -= share * ewald_real_stresslet_apply(r, xi, q.row(s).transpose(), n.row(s).transpose()).transpose();
        }
      }
      for (std::vector<double>* kept : {static_cast<std::vector<double>*>(nullptr), &single}) {
        const PointField s_shared = real_space_single_layer(pairs, xi, f, kept, &shares);
        EXPECT_LT((s_shared - s_ref).norm(), 1e-12 * s_ref.norm()) << "cutoff " << cutoff << ", seed " << seed;
      }
      for (std::vector<double>* kept : {static_cast<std::vector<double>*>(nullptr), &double_}) {
        const PointField d_shared = real_space_double_layer(pairs, xi, q, n, kept, &shares);
        EXPECT_LT((d_shared - d_ref).norm(), 1e-12 * d_ref.norm()) << "cutoff " << cutoff << ", seed " << seed;
      }
    }
  }
}

// from_lists keeps each entry's source and share whatever the sources' spread: a segment
// numbers its nodes from its first source in 16 bits (PatchNode), so sources further apart,
// or below the first, start a segment of their own.
TEST(RealSpaceSum, PairSharesFromListsKeepEverySource) {
  const std::vector<int> sources = {5, 65540, 70000, 3, 140000, 140001};
  const std::vector<float> shares = {0.5f, 0.25f, 0.125f, 0.75f, 0.375f, 0.0625f};
  const PairShares p = PairShares::from_lists({0, 0, 6}, sources, shares);  // target 0 has none
  ASSERT_EQ(p.offsets, (std::vector<std::int64_t>{0, 0, 4}));
  std::vector<int> got_sources;
  std::vector<float> got_shares;
  for (const PairShares::Segment& g : p.segments)
    for (int e = 0; e < g.count; ++e) {
      got_sources.push_back(g.first_source + g.nodes[e].node());
      got_shares.push_back(g.nodes[e].eta());
    }
  EXPECT_EQ(got_sources, sources);
  EXPECT_EQ(got_shares, shares);
}

TEST(RealSpaceSum, RejectsSharesThatDoNotFit) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  const PointField x = random_points(10, Eigen::Vector3d::Ones(), 1);
  const NeighborList pairs(box, 0.3, x, x);
  const PairShares wrong_targets = PairShares::from_lists({0, 0, 0}, {}, {});
  EXPECT_THROW(real_space_single_layer(pairs, 5.0, random_vectors(10, 1), nullptr, &wrong_targets),
               std::invalid_argument);
  std::vector<std::int64_t> offsets(11, 1);
  offsets[0] = 0;
  const PairShares bad_source = PairShares::from_lists(offsets, {10}, {0.5f});
  EXPECT_THROW(real_space_double_layer(pairs, 5.0, random_vectors(10, 1), random_vectors(10, 2), nullptr, &bad_source),
               std::invalid_argument);
}

TEST(RealSpaceSum, RejectsMismatchedDensities) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  const PointField x = random_points(10, Eigen::Vector3d::Ones(), 1);
  const NeighborList pairs(box, 0.3, x, x);
  EXPECT_THROW(real_space_single_layer(pairs, 5.0, random_vectors(9, 1)), std::invalid_argument);
  EXPECT_THROW(real_space_double_layer(pairs, 5.0, random_vectors(10, 1), random_vectors(8, 2)),
               std::invalid_argument);
}

TEST(RealSpaceSum, RejectsANonPositiveSplittingParameter) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  const PointField x = random_points(10, Eigen::Vector3d::Ones(), 1);
  const NeighborList pairs(box, 0.3, x, x);
  EXPECT_THROW(real_space_single_layer(pairs, 0.0, random_vectors(10, 1)), std::invalid_argument);
  EXPECT_THROW(real_space_double_layer(pairs, -1.0, random_vectors(10, 1), random_vectors(10, 2)),
               std::invalid_argument);
}
