#include <gtest/gtest.h>
#include <omp.h>

#include <numeric>

#include "libsolver/spme/bspline.h"
#include "libsolver/spme/spme_stencils.h"
#include "test_points.h"

using namespace rbcflow;
using test::random_points;
using test::random_vectors;

namespace {
const Eigen::Vector3d kL(1.0, 0.9, 1.3);
const PeriodicBox kBox(kL);

std::vector<double> interleave(const PointField& f) {
  std::vector<double> out(3 * f.rows());
  for (int i = 0; i < f.rows(); ++i)
    for (int c = 0; c < 3; ++c) out[3 * i + c] = f(i, c);
  return out;
}
}  // namespace

// Spreading conserves each component's total (the weights are a partition of unity), for
// every order, and points outside the box are folded in.
TEST(SpmeStencils, SpreadingConservesTotals) {
  for (int p : {4, 5, 8, 10}) {
    const SpmeGrid grid(kBox, EwaldParameters{5.0, 0.3, {20, 24, 30}, p});
    PointField x = random_points(200, kL, 1);
    x.row(0) << -0.3, 2.5, 7.0;
    const PointField f = random_vectors(200, 2);
    const SpmeStencils stencils(grid, x);
    std::vector<double> g(3 * grid.slab_points());
    stencils.spread<3>(interleave(f).data(), g.data());
    for (int c = 0; c < 3; ++c) {
      double total = 0;
      for (std::size_t i = 0; i < grid.slab_points(); ++i) total += g[3 * i + c];  // rows' padding: 0
      EXPECT_NEAR(total, f.col(c).sum(), 1e-12) << "p = " << p;
    }
  }
}

// A point on a grid node: weights M_p(j) at the nodes around it (j = 1 .. p-1).
TEST(SpmeStencils, PointOnANode) {
  const int p = 4;
  const SpmeGrid grid(kBox, EwaldParameters{5.0, 0.3, {16, 16, 16}, p});
  PointField x(1, 3);
  x << 5.0 / 16 * kL[0], 7.0 / 16 * kL[1], 9.0 / 16 * kL[2];
  const SpmeStencils stencils(grid, x);
  std::vector<double> g(3 * grid.slab_points());
  const double f[3] = {1.0, 0.0, 0.0};
  stencils.spread<3>(f, g.data());
  // Nodes 5 - j along each direction, weight M_4(j): 1/6, 2/3, 1/6 for j = 1, 2, 3; the rows
  // of the grid array are padded to 18 points (FFTW's in-place layout).
  ASSERT_EQ(grid.row_stride(), 18);
  const auto node = [&](int i, int j, int l) {
    return g[3 * ((static_cast<std::size_t>(i) * 16 + j) * 18 + l)];
  };
  EXPECT_NEAR(node(3, 5, 7), bspline(p, 2) * bspline(p, 2) * bspline(p, 2), 1e-15);
  EXPECT_NEAR(node(4, 6, 8), bspline(p, 1) * bspline(p, 1) * bspline(p, 1), 1e-15);
  EXPECT_NEAR(node(5, 7, 9), 0.0, 1e-15);
}

// Interpolation of a constant field is exact; of spread densities it is the adjoint of
// spreading: <interpolate(g), f> = <g, spread(f)>.
TEST(SpmeStencils, InterpolationIsTheAdjointOfSpreading) {
  const SpmeGrid grid(kBox, EwaldParameters{5.0, 0.3, {20, 24, 30}, 6});
  const PointField x = random_points(100, kL, 3), f = random_vectors(100, 4);
  const SpmeStencils stencils(grid, x);
  std::vector<double> g(3 * grid.slab_points(), 2.5);
  PointField u;
  stencils.interpolate(g.data(), u);
  EXPECT_LT((u.array() - 2.5).abs().maxCoeff(), 1e-13);
  for (std::size_t i = 0; i < g.size(); ++i) g[i] = std::sin(0.37 * static_cast<double>(i));
  stencils.interpolate(g.data(), u);
  std::vector<double> spread(g.size());
  stencils.spread<3>(interleave(f).data(), spread.data());
  const double lhs = (u.array() * f.array()).sum();
  const double rhs = std::inner_product(g.begin(), g.end(), spread.begin(), 0.0);
  EXPECT_NEAR(lhs, rhs, 1e-11 * std::abs(rhs));
}

// The coloured parallel spreading gives the same grid, bit for bit, with 1 and 2 threads.
TEST(SpmeStencils, ParallelSpreadingIsRaceFreeAndDeterministic) {
  const SpmeGrid grid(kBox, EwaldParameters{5.0, 0.3, {30, 24, 30}, 6});
  const PointField x = random_points(5000, kL, 5), f = random_vectors(5000, 6);
  const SpmeStencils stencils(grid, x);
  const std::vector<double> density = interleave(f);
  std::vector<double> one(3 * grid.slab_points()), two(one.size());
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  stencils.spread<3>(density.data(), one.data());
  omp_set_num_threads(2);
  stencils.spread<3>(density.data(), two.data());
  omp_set_num_threads(threads);
  EXPECT_EQ(one, two);
}
