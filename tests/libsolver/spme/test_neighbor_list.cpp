#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "libsolver/spme/neighbor_list.h"
#include "test_points.h"

using namespace rbcflow;
using test::random_points;

namespace {

using Pair = std::tuple<int, double, double, double>;  // caller's source index, r

std::vector<Pair> listed_pairs(const NeighborList& list, int t) {
  std::vector<Pair> pairs;
  list.for_each_neighbor(t, [&](int s, const Eigen::Vector3d& r) {
    pairs.emplace_back(list.order()[s], r[0], r[1], r[2]);
  });
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

// Every source image within the cutoff, by brute force.
std::vector<Pair> brute_force_pairs(const PeriodicBox& box, double cutoff, const PointField& xs,
                                    const Eigen::Vector3d& xt, double coincidence) {
  std::vector<Pair> pairs;
  const Eigen::Vector3d L = box.lengths();
  const Eigen::Vector3i m(static_cast<int>(std::ceil(cutoff / L[0])),
                          static_cast<int>(std::ceil(cutoff / L[1])),
                          static_cast<int>(std::ceil(cutoff / L[2])));
  for (int s = 0; s < xs.rows(); ++s) {
    const Eigen::Vector3d d = box.wrap(xs.row(s).transpose()) - box.wrap(xt);
    for (int a = -m[0]; a <= m[0]; ++a)
      for (int b = -m[1]; b <= m[1]; ++b)
        for (int c = -m[2]; c <= m[2]; ++c) {
          const Eigen::Vector3d r = d + Eigen::Vector3d(a * L[0], b * L[1], c * L[2]);
          if (r.norm() < cutoff && r.norm() > coincidence) pairs.emplace_back(s, r[0], r[1], r[2]);
        }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

void expect_same_pairs(const PeriodicBox& box, double cutoff, const PointField& xs,
                       const PointField& xt) {
  const NeighborList list(box, cutoff, xs, xt);
  ASSERT_EQ(list.n_targets(), xt.rows());
  std::int64_t total = 0;
  for (int t = 0; t < xt.rows(); ++t) {
    const std::vector<Pair> a = listed_pairs(list, t);
    const std::vector<Pair> b =
        brute_force_pairs(box, cutoff, xs, xt.row(t).transpose(), list.coincidence_distance());
    ASSERT_EQ(a.size(), b.size()) << "target " << t;
    for (std::size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(std::get<0>(a[i]), std::get<0>(b[i]));
      EXPECT_NEAR(std::get<1>(a[i]), std::get<1>(b[i]), 1e-12);
      EXPECT_NEAR(std::get<2>(a[i]), std::get<2>(b[i]), 1e-12);
      EXPECT_NEAR(std::get<3>(a[i]), std::get<3>(b[i]), 1e-12);
    }
    total += static_cast<std::int64_t>(a.size());
  }
  EXPECT_EQ(total, list.n_pairs());
}

}  // namespace

TEST(NeighborList, SmallCutoffMatchesBruteForce) {
  const Eigen::Vector3d L(1.0, 1.0, 1.0);
  expect_same_pairs(PeriodicBox(L), 0.2, random_points(400, L, 1), random_points(150, L, 2));
}

// Cutoff beyond half (and beyond the whole of) some box sides: every image is listed.
TEST(NeighborList, LargeCutoffListsAllImages) {
  const Eigen::Vector3d L(1.0, 0.6, 0.8);
  expect_same_pairs(PeriodicBox(L), 0.9, random_points(60, L, 3), random_points(40, L, 4));
  expect_same_pairs(PeriodicBox(L), 2.1, random_points(10, L, 5), random_points(7, L, 6));
}

// 160,000 sources in a box 4 search cells thick: a target's pairs jump by tens of thousands of
// source indices between planes of cells (beyond the 16-bit steps of the coded list) and
// change images across the thin side; the pairs are still exactly the brute-force ones. The
// list holds under 3 bytes a pair besides 40 a point (positions, orders, offsets).
TEST(NeighborList, CodedPairsSurviveLongStepsAndImageChanges) {
  const Eigen::Vector3d L(0.2, 3.0, 3.0);
  const PointField xs = random_points(160000, L, 11), xt = random_points(40, L, 12);
  expect_same_pairs(PeriodicBox(L), 0.1, xs, xt);
  const NeighborList many(PeriodicBox(L), 0.1, xs, xs);
  EXPECT_GT(many.n_pairs(), 200 * xs.rows());
  EXPECT_LT(static_cast<double>(many.memory_bytes()), 3.0 * many.n_pairs() + 40.0 * 2 * xs.rows());
}

// Targets equal to the sources: the r = 0 pair is left out, the source's other images are not.
TEST(NeighborList, CoincidentPairsAreSkipped) {
  const Eigen::Vector3d L(1.0, 1.0, 1.0);
  const PointField x = random_points(50, L, 7);
  expect_same_pairs(PeriodicBox(L), 1.2, x, x);
  const NeighborList list(PeriodicBox(L), 0.3, x, x);
  for (int t = 0; t < x.rows(); ++t)
    list.for_each_neighbor(t, [&](int, const Eigen::Vector3d& r) { EXPECT_GT(r.norm(), 0.0); });
}

// Positions outside the box are folded back: shifting by lattice vectors changes nothing.
TEST(NeighborList, PositionsAreTakenModuloTheBox) {
  const Eigen::Vector3d L(1.0, 2.0, 1.5);
  const PointField xs = random_points(100, L, 8), xt = random_points(30, L, 9);
  PointField xs_shifted = xs;
  xs_shifted.col(0).array() += 3.0 * L[0];
  xs_shifted.col(2).array() -= 2.0 * L[2];
  const NeighborList a(PeriodicBox(L), 0.4, xs, xt), b(PeriodicBox(L), 0.4, xs_shifted, xt);
  ASSERT_EQ(a.n_pairs(), b.n_pairs());
  for (int t = 0; t < xt.rows(); ++t) {
    const std::vector<Pair> pa = listed_pairs(a, t), pb = listed_pairs(b, t);
    ASSERT_EQ(pa.size(), pb.size());
    for (std::size_t i = 0; i < pa.size(); ++i)
      EXPECT_NEAR(std::get<1>(pa[i]), std::get<1>(pb[i]), 1e-12);
  }
}

TEST(NeighborList, RejectsBadCutoffs) {
  const PeriodicBox box(Eigen::Vector3d::Ones());
  const PointField x = random_points(5, Eigen::Vector3d::Ones(), 1);
  EXPECT_THROW(NeighborList(box, 0.0, x, x), std::invalid_argument);
  EXPECT_THROW(NeighborList(box, 17.0, x, x), std::invalid_argument);
}
