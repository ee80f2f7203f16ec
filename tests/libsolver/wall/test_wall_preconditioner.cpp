#include "libsolver/wall/wall_preconditioner.h"

#include <gtest/gtest.h>

#include <Eigen/SparseLU>
#include <algorithm>
#include <memory>
#include <numeric>
#include <vector>

#include "geometry/vessel/vessel.h"
#include "libsolver/wall/near_field.h"
#include "libsolver/wall/wall_solver.h"

using namespace rbcflow;

namespace {

// A D = 3.2 tube along z, 4 x 4 x 6 box, h = 0.4: about 500 nodes.
std::shared_ptr<const WallElements> tube_wall() {
  TubeSpec spec;
  spec.diameter = 3.2;
  spec.box = Eigen::Vector3d(4.0, 4.0, 6.0);
  spec.element_size = 0.4;
  return std::make_shared<const WallElements>(tube(spec));
}

Eigen::VectorXd smooth_vector(const PointField& nodes) {
  Eigen::VectorXd r(3 * nodes.rows());
  for (Eigen::Index i = 0; i < nodes.rows(); ++i)
    r.segment<3>(3 * i) << std::sin(nodes(i, 2)), std::cos(nodes(i, 0) + nodes(i, 2)), 1.0 + 0.2 * nodes(i, 1);
  return r;
}

}  // namespace

TEST(WallPreconditioner, BlockCounts) {
  EXPECT_EQ(wall_preconditioner_blocks(500, 500), 1);
  EXPECT_EQ(wall_preconditioner_blocks(501, 500), 2);
  EXPECT_EQ(wall_preconditioner_blocks(21692, 500), 44);
  EXPECT_EQ(wall_preconditioner_blocks(10, 1), 10);
  EXPECT_THROW(wall_preconditioner_blocks(10, 0), std::invalid_argument);
}

// One block is the sparse LU of the whole local near field: the same bits as Eigen's.
TEST(WallPreconditioner, OneBlockIsTheWholeLocalNearField) {
  const auto e = tube_wall();
  const PointField& nodes = e->wall.surface.points;
  const NearField near = near_field(*e, nodes);
  const WallPreconditioner m(near.local, nodes, static_cast<int>(nodes.rows()), Communicator{});
  ASSERT_EQ(m.blocks(), 1);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> whole(near.local);
  const Eigen::VectorXd r = smooth_vector(nodes);
  const OwnedSegments segments(static_cast<int>(nodes.rows()), Communicator{});
  const Eigen::VectorXd expected = whole.solve(r);
  EXPECT_EQ(m.solve_mine(r, segments), expected);
  EXPECT_EQ(m.bytes(), static_cast<std::size_t>(whole.nnzL() + whole.nnzU()) * (sizeof(double) + sizeof(int)));
}

// Several blocks: slabs along the tube (its longest extent) of equal node counts, and the
// result solves the block-diagonal part of the local near field, built here independently from
// the slabs' bounds.
TEST(WallPreconditioner, BlocksAreSlabsAndSolveTheBlockDiagonal) {
  const auto e = tube_wall();
  const PointField& nodes = e->wall.surface.points;
  const int n = static_cast<int>(nodes.rows());
  const NearField near = near_field(*e, nodes);
  const int block_nodes = 100;
  const WallPreconditioner m(near.local, nodes, block_nodes, Communicator{});
  const int blocks = (n + block_nodes - 1) / block_nodes;
  ASSERT_GE(blocks, 4);
  EXPECT_EQ(m.blocks(), blocks);
  // The slabs: the k-th node along z (ties by index) is in block floor-ish k / (n / blocks).
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return nodes(a, 2) < nodes(b, 2); });
  std::vector<int> block_of(n);
  for (int b = 0, k = 0; b < blocks; ++b)
    for (int size = n / blocks + (b < n % blocks ? 1 : 0); size > 0; --size) block_of[order[k++]] = b;
  std::vector<Eigen::Triplet<double>> kept;
  long dropped = 0;
  for (int col = 0; col < near.local.outerSize(); ++col)
    for (Eigen::SparseMatrix<double>::InnerIterator it(near.local, col); it; ++it) {
      if (block_of[it.row() / 3] == block_of[col / 3]) kept.emplace_back(it.row(), col, it.value());
      else ++dropped;
    }
  EXPECT_GT(dropped, 0);  // the slabs cut the near field's couplings
  Eigen::SparseMatrix<double> diagonal(3 * n, 3 * n);
  diagonal.setFromTriplets(kept.begin(), kept.end());
  const Eigen::VectorXd r = smooth_vector(nodes);
  const Eigen::VectorXd z = m.solve_mine(r, OwnedSegments(n, Communicator{}));
  // LU solves of blocks of condition ~1e2-1e3: residual at rounding.
  EXPECT_LT((diagonal * z - r).norm() / r.norm(), 1e-12);
  // ... and not the whole local part's solution.
  EXPECT_GT((near.local * z - r).norm() / r.norm(), 1e-6);
}

// The wall solve with blocks converges to the one-block solve's force, to GMRES's tolerance.
TEST(WallPreconditioner, BlockedSolveReachesTheSameForce) {
  const auto e = tube_wall();
  const PeriodicBox box(Eigen::Vector3d(4.0, 4.0, 6.0));
  const PointField v = Eigen::RowVector3d(0.1, 0.0, 1.0).replicate(e->num_nodes(), 1);
  WallSolveOptions whole, blocked;
  whole.preconditioner_block_nodes = static_cast<int>(e->num_nodes());
  blocked.preconditioner_block_nodes = 100;
  whole.tolerance = blocked.tolerance = 1e-10;
  const auto assembled = WallOperator::RealSpace::assembled;
  WallSolver a(WallOperator(e, e->wall.surface.points, box, 1e-6, nullptr, assembled), whole);
  WallSolver b(WallOperator(e, e->wall.surface.points, box, 1e-6, nullptr, assembled), blocked);
  EXPECT_EQ(a.preconditioner_blocks(), 1);
  EXPECT_GE(b.preconditioner_blocks(), 4);
  const WallSolution fa = a.solve(v, 1.0, whole), fb = b.solve(v, 1.0, blocked);
  const double d = (fa.force - fb.force).cwiseAbs().maxCoeff() / fa.force.cwiseAbs().maxCoeff();
  std::printf("  %d iterations with one block, %d with %d blocks; force %.1e apart\n", fa.gmres.iterations,
              fb.gmres.iterations, b.preconditioner_blocks(), d);
  // Both residuals below 1e-10 of the right-hand side; the operator's condition (~1e2 on this
  // wall) bounds the force's difference by ~1e-8.
  EXPECT_LT(d, 1e-7);
}
