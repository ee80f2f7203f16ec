#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include "tests/libsolver/spme/ewald_direct.h"
#include "libsolver/spme/spme_plan.h"
#include "test_points.h"

using namespace rbcflow;
using test::random_points;
using test::random_unit_vectors;
using test::random_vectors;

namespace {
const Eigen::Vector3d kL(1.0, 1.0, 1.0);
const PeriodicBox kBox(kL);

struct Data {
  PointField xs = random_points(300, kL, 1), xt = random_points(300, kL, 2);
  PointField f = random_vectors(300, 3), q = random_vectors(300, 4),
             n = random_unit_vectors(300, 5);
};
const Data& data() {
  static const Data d;
  return d;
}
}  // namespace

// The SPME grid error decreases as h^p (docs/references.md section 2): smooth part against the
// direct Fourier sum with the same xi, K = 32 -> 64 (xi h = 0.125 -> 0.0625, where the
// truncation beyond the Nyquist wavenumber is negligible), orders 4, 6, 8, both layers.
TEST(SpmePlan, GridErrorDecreasesAsHToThePowerP) {
  const Data& d = data();
  const double xi = 4.0;
  const EwaldDirect direct(kBox, xi);
  const PointField ref_s = direct.fourier_single_layer(d.xs, d.f, d.xt);
  const PointField ref_d = direct.fourier_double_layer(d.xs, d.q, d.n, d.xt);
  for (int p : {4, 6, 8}) {
    double error_s[2], error_d[2];
    const int sides[2] = {32, 64};
    for (int i = 0; i < 2; ++i) {
      const int K = sides[i];
      SpmePlan plan(std::make_shared<const SpmeGrid>(kBox, EwaldParameters{xi, 0.1, {K, K, K}, p}),
                    d.xs, d.xt);
      error_s[i] = test::rms_difference(plan.single_layer(d.f), ref_s);
      error_d[i] = test::rms_difference(plan.double_layer(d.q, d.n), ref_d);
    }
    const double order_s = std::log2(error_s[0] / error_s[1]),
                 order_d = std::log2(error_d[0] / error_d[1]);
    std::printf(
        "p = %d: RMS error K = 32 -> 64: single layer %.2e -> %.2e (order %.2f), "
        "double layer %.2e -> %.2e (order %.2f)\n",
        p, error_s[0], error_s[1], order_s, error_d[0], error_d[1], order_d);
    EXPECT_NEAR(order_s, p, 0.5);
    EXPECT_NEAR(order_d, p, 0.5);
  }
}

// A fine grid reproduces the direct Fourier sum in a non-cubic box, with odd and even orders.
TEST(SpmePlan, MatchesDirectFourierSumInANonCubicBox) {
  const Eigen::Vector3d L(1.2, 0.7, 1.0);
  const PeriodicBox box(L);
  const PointField xs = random_points(150, L, 6), xt = random_points(80, L, 7);
  const PointField f = random_vectors(150, 8), q = random_vectors(150, 9),
                   n = random_unit_vectors(150, 10);
  const double xi = 5.0;
  const EwaldDirect direct(box, xi);
  const PointField ref_s = direct.fourier_single_layer(xs, f, xt),
                   ref_d = direct.fourier_double_layer(xs, q, n, xt);
  for (int p : {7, 10}) {
    SpmePlan plan(std::make_shared<const SpmeGrid>(box, EwaldParameters{xi, 0.1, {60, 36, 50}, p}),
                  xs, xt);
    // xi h = 0.1: grid error ~1e-9 relative (p = 7), 1e-12 (p = 10).
    const double tol = p == 7 ? 1e-8 : 1e-11;
    EXPECT_LT(test::rms_difference(plan.single_layer(f), ref_s),
              tol * ref_s.norm() / std::sqrt(80.0))
        << p;
    EXPECT_LT(test::rms_difference(plan.double_layer(q, n), ref_d),
              tol * ref_d.norm() / std::sqrt(80.0))
        << p;
  }
}

// Shared stencils (targets = sources) give what separate ones do; results do not depend on
// the thread count beyond rounding.
TEST(SpmePlan, SharedStencilsAndThreadCount) {
  const Data& d = data();
  const auto grid =
      std::make_shared<const SpmeGrid>(kBox, EwaldParameters{6.0, 0.1, {32, 32, 32}, 6});
  SpmePlan shared(grid, d.xs), separate(grid, d.xs, d.xs);
  const PointField a = shared.single_layer(d.f);
  EXPECT_LT((a - separate.single_layer(d.f)).norm(), 1e-14 * a.norm());
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto grid1 =
      std::make_shared<const SpmeGrid>(kBox, EwaldParameters{6.0, 0.1, {32, 32, 32}, 6});
  SpmePlan serial(grid1, d.xs);
  const PointField b = serial.double_layer(d.q, d.n);
  omp_set_num_threads(threads);
  EXPECT_LT((b - shared.double_layer(d.q, d.n)).norm(), 1e-13 * b.norm());
}

// Lean transforms (the off-diagonal density a component at a time) give the double layer of the
// three components at once, to rounding, in a distributed-free non-cubic grid; the work they
// report is an array of one grid less two.
TEST(SpmePlan, LeanTransformsGiveTheSameDoubleLayer) {
  const Data& d = data();
  const auto grid = std::make_shared<const SpmeGrid>(kBox, EwaldParameters{6.0, 0.1, {32, 28, 36}, 8});
  SpmePlan plan(grid, d.xs, d.xt);
  const PointField together = plan.double_layer(d.q, d.n);
  const std::size_t work = plan.work_bytes(6);
  plan.transform_lean(true);
  const PointField lean = plan.double_layer(d.q, d.n);
  EXPECT_LT((lean - together).norm(), 1e-14 * together.norm());
  EXPECT_EQ(work - plan.work_bytes(6), 2 * grid->buffer_size(1) * sizeof(fftw_complex));
}

// Products whose work arrays come from a keeping pool reuse the array of earlier products,
// written by them (spreading zeroes what it uses): the same results to the bit as with fresh
// arrays; what waits between products is the array of three grids alone.
TEST(SpmePlan, KeptWorkArraysGiveTheSameProducts) {
  const Data& d = data();
  const EwaldParameters p{6.0, 0.1, {32, 28, 36}, 8};
  const auto fresh_grid = std::make_shared<const SpmeGrid>(kBox, p);
  auto pool = std::make_shared<WorkArrayPool>();
  pool->keep(true);
  const auto kept_grid = std::make_shared<const SpmeGrid>(kBox, p, FftPlanning::estimate, Communicator{}, pool);
  SpmePlan fresh(fresh_grid, d.xs, d.xt), kept(kept_grid, d.xs, d.xt);
  fresh.transform_lean(true);
  kept.transform_lean(true);
  const PointField single = fresh.single_layer(d.f), double_layer = fresh.double_layer(d.q, d.n);
  for (int round = 0; round < 2; ++round) {
    EXPECT_EQ((kept.double_layer(d.q, d.n) - double_layer).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ((kept.single_layer(d.f) - single).cwiseAbs().maxCoeff(), 0.0);
  }
  EXPECT_EQ(pool->waiting_bytes(), kept_grid->buffer_size(3) * sizeof(fftw_complex));
}

// The grid's directions in any order of the box's axes (spme_grid.h: a distributed grid puts
// the axis of most grid points first) relabel the sums only: in a box of three different
// sides with three different grid sizes, every order gives the products of the box's own
// order to rounding, both layers, at other targets and at the sources.
TEST(SpmePlan, GridAxesInAnyOrderGiveTheSameProducts) {
  const Data& d = data();
  const PeriodicBox box(Eigen::Vector3d(1.0, 0.8, 1.3));
  const EwaldParameters p{6.0, 0.1, {32, 28, 36}, 8};
  const auto natural = std::make_shared<const SpmeGrid>(box, p);
  SpmePlan one(natural, d.xs, d.xt), one_self(natural, d.xs);
  const PointField single = one.single_layer(d.f), double_layer = one.double_layer(d.q, d.n),
                   self = one_self.double_layer(d.q, d.n);
  std::array<int, 3> axes{0, 1, 2};
  double largest = 0;
  const auto relative = [&](const PointField& a, const PointField& b) {
    const double r = (a - b).norm() / b.norm();
    largest = std::max(largest, r);
    return r;
  };
  do {
    const auto grid =
        std::make_shared<const SpmeGrid>(box, p, FftPlanning::estimate, Communicator{}, nullptr, axes);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(grid->axis(k), axes[k]);
      EXPECT_EQ(grid->size(k), p.grid[axes[k]]);
    }
    SpmePlan plan(grid, d.xs, d.xt), plan_self(grid, d.xs);
    EXPECT_LT(relative(plan.single_layer(d.f), single), 1e-13);
    EXPECT_LT(relative(plan.double_layer(d.q, d.n), double_layer), 1e-13);
    EXPECT_LT(relative(plan_self.double_layer(d.q, d.n), self), 1e-13);
  } while (std::next_permutation(axes.begin(), axes.end()));
  std::printf("  largest relative difference over the six orders: %.1e\n", largest);
  EXPECT_THROW(SpmeGrid(box, p, FftPlanning::estimate, Communicator{}, nullptr, std::array<int, 3>{0, 0, 2}),
               std::invalid_argument);
}

TEST(SpmePlan, RejectsMismatchedDensities) {
  const Data& d = data();
  SpmePlan plan(std::make_shared<const SpmeGrid>(kBox, EwaldParameters{6.0, 0.1, {16, 16, 16}, 4}),
                d.xs, d.xt);
  EXPECT_THROW(plan.single_layer(random_vectors(10, 1)), std::invalid_argument);
  EXPECT_THROW(plan.double_layer(d.q, random_vectors(10, 1)), std::invalid_argument);
}

// Sources whose forces are a fixed linear map of fewer unknowns (3 of 100 each, as the wall's
// Gauss points of its nodal densities), spread through SpmeStencils::spreading_matrix: the
// same single layer as spreading map x point by point, to rounding. The points of an unknown
// lie anywhere in the box, so its stencils span more than the grid and fold onto it.
TEST(SpmePlan, SpreadingMatrixGivesTheSameSingleLayer) {
  const Data& d = data();
  std::mt19937 gen(9);
  std::uniform_int_distribution<int> pick(0, 99);
  std::uniform_real_distribution<double> weight(0.1, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < d.xs.rows(); ++i)
    for (int a = 0; a < 3; ++a) entries.emplace_back(i, pick(gen), weight(gen));
  Eigen::SparseMatrix<double, Eigen::RowMajor> map(d.xs.rows(), 100);
  map.setFromTriplets(entries.begin(), entries.end());
  const PointField x = random_vectors(100, 11);
  const PointField forces = map * x;
  for (const std::array<int, 3> K : {std::array<int, 3>{32, 32, 32}, std::array<int, 3>{16, 18, 20}}) {
    SpmePlan plan(std::make_shared<const SpmeGrid>(kBox, EwaldParameters{4.0, 0.1, K, 8}), d.xs, d.xt);
    const PointField expected = plan.single_layer(forces);
    const PointField u = plan.single_layer(plan.sources().spreading_matrix(map), x);
    EXPECT_LT((u - expected).norm(), 1e-13 * expected.norm()) << K[0] << " x " << K[1] << " x " << K[2];
  }
  EXPECT_THROW(SpmePlan(std::make_shared<const SpmeGrid>(kBox, EwaldParameters{4.0, 0.1, {16, 16, 16}, 6}), d.xs, d.xt)
                   .sources()
                   .spreading_matrix(Eigen::SparseMatrix<double, Eigen::RowMajor>(5, 3)),
               std::invalid_argument);
}
