#include "libsolver/wall/symmetric_block_matrix.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "geometry/vessel/vessel.h"
#include "libsolver/spme/ewald_parameters.h"
#include "libsolver/wall/near_field.h"
#include "libsolver/wall/wall_operator.h"
#include "libsolver/wall/wall_real_space.h"

using namespace rbcflow;

namespace {

// n_targets x n_nodes random symmetric 3x3 blocks, each present with probability 0.3.
Eigen::SparseMatrix<double, Eigen::RowMajor> random_symmetric_blocks(int n_targets, int n_nodes, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int t = 0; t < n_targets; ++t)
    for (int n = 0; n < n_nodes; ++n) {
      if (u(gen) < 0.4) continue;
      Eigen::Matrix3d b;
      for (int k = 0; k < 3; ++k)
        for (int l = k; l < 3; ++l) b(k, l) = b(l, k) = u(gen);
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) entries.emplace_back(3 * t + k, 3 * n + l, b(k, l));
    }
  Eigen::SparseMatrix<double, Eigen::RowMajor> m(3 * n_targets, 3 * n_nodes);
  m.setFromTriplets(entries.begin(), entries.end());
  return m;
}

}  // namespace

// The block product equals the scalar sparse product to rounding.
TEST(SymmetricBlockMatrix, ProductEqualsTheScalarSparseProduct) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> m = random_symmetric_blocks(60, 45, 3);
  const SymmetricBlockMatrix b(m);
  EXPECT_EQ(b.num_targets(), 60);
  EXPECT_EQ(b.num_nodes(), 45);
  EXPECT_EQ(b.num_blocks() * 9, m.nonZeros());
  const Eigen::VectorXd f = Eigen::VectorXd::Random(3 * 45);
  const Eigen::VectorXd expected = m * f;
  EXPECT_LT((b * f - expected).norm(), 1e-14 * expected.norm());
}

// The wall operator's assembled matrices are made of symmetric blocks: the near-field
// correction plus the real-space part of a small periodic tube converts, and its product
// equals the scalar one, whether converted from the scalar matrix or assembled row by row.
TEST(SymmetricBlockMatrix, HoldsTheWallNearFieldAndRealSpaceParts) {
  const Eigen::Vector3d side(3.0, 3.0, 2.0);
  const WallElements e(tube(TubeSpec{2.0, 2, side, 0.4}));
  const PeriodicBox box(side);
  const PointField& nodes = e.wall.surface.points;
  const EwaldChoice c = choose_ewald_parameters(EwaldKernel::stokeslet, 1e-7, box, e.points.rows(), nodes.rows(),
                                                kAssembledRealSpace);
  PointField sources(e.points.rows(), 3), targets(nodes.rows(), 3);
  for (Eigen::Index i = 0; i < sources.rows(); ++i) sources.row(i) = box.wrap(e.points.row(i).transpose()).transpose();
  for (Eigen::Index i = 0; i < targets.rows(); ++i) targets.row(i) = box.wrap(nodes.row(i).transpose()).transpose();
  const NeighborList pairs(box, c.parameters.cutoff, sources, targets);
  const Eigen::SparseMatrix<double, Eigen::RowMajor> m =
      near_field(e, nodes).correction + wall_real_space_matrix(e, pairs, c.parameters.xi);
  const SymmetricBlockMatrix b(m);
  const Eigen::VectorXd f = Eigen::VectorXd::Random(3 * e.num_nodes());
  const Eigen::VectorXd expected = m * f;
  EXPECT_LT((b * f - expected).norm(), 1e-14 * expected.norm());
  // Assembled row by row (the operator's way), without the scalar matrix: the same blocks.
  const Eigen::SparseMatrix<double, Eigen::RowMajor> near = near_field(e, nodes).correction;
  const int n = static_cast<int>(nodes.rows());
  const SymmetricBlockMatrix rows = wall_real_space_blocks(e, pairs, c.parameters.xi, near, OwnedRange{0, n});
  EXPECT_EQ(rows.num_blocks(), b.num_blocks());
  EXPECT_LT((rows * f - expected).norm(), 1e-14 * expected.norm());
  // Two ranks' shares of the rows: each only its own, and together the whole product exactly.
  const SymmetricBlockMatrix first = wall_real_space_blocks(e, pairs, c.parameters.xi, near, owned_block(n, 0, 2));
  const SymmetricBlockMatrix second = wall_real_space_blocks(e, pairs, c.parameters.xi, near, owned_block(n, 1, 2));
  EXPECT_EQ(first.num_blocks() + second.num_blocks(), rows.num_blocks());
  const Eigen::VectorXd a = first * f, z = second * f, whole = rows * f;
  EXPECT_TRUE(a.tail(3 * (n - owned_block(n, 0, 2).end)).isZero(0.0));
  EXPECT_TRUE(z.head(3 * owned_block(n, 1, 2).begin).isZero(0.0));
  EXPECT_EQ(a + z, whole);
  // In single precision (WallOperator's form for tolerances of kSingleBlocksTolerance = 1e-6
  // and more): the products of random and of smooth densities stay within the tenth of the
  // tolerance the assembled part is built for (kAssembledToleranceFactor); measured 2.8e-8 and
  // 1.7e-8.
  const SymmetricBlockMatrix single = wall_real_space_blocks(e, pairs, c.parameters.xi, near, OwnedRange{0, n},
                                                             SymmetricBlockMatrix::Precision::single_entries);
  PointField smooth(n, 3);
  for (int i = 0; i < n; ++i) smooth.row(i) << 1.0, 0.3 * std::sin(nodes(i, 2)), 0.2 * std::cos(nodes(i, 0));
  const Eigen::MatrixXd by_node = smooth.transpose();  // index 3 i + k
  const Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(by_node.data(), 3 * n);
  for (const Eigen::VectorXd* density : {&f, &g}) {
    const Eigen::VectorXd exact = rows * *density;
    const double moved = (single * *density - exact).norm() / exact.norm();
    std::printf("single-precision blocks: product moved by %.2e of its norm\n", moved);
    EXPECT_LT(moved, kAssembledToleranceFactor * kSingleBlocksTolerance);
  }
}

// Single-precision entries: the product is that of the matrix with each entry rounded to float
// (the sums in double), so each row moves by at most 2^-24 of the sum of its terms' magnitudes.
TEST(SymmetricBlockMatrix, SingleEntriesAreTheRoundedMatrix) {
  const Eigen::SparseMatrix<double, Eigen::RowMajor> m = random_symmetric_blocks(60, 45, 5);
  const int nt = 60, nn = 45;
  const auto row = [&m](int t, SymmetricBlockMatrix::Row& blocks) {
    for (int n = 0; n < 45; ++n) {
      Eigen::Matrix3d b;
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l) b(k, l) = m.coeff(3 * t + k, 3 * n + l);
      if (!b.isZero(0.0)) blocks.emplace_back(n, b);
    }
  };
  const SymmetricBlockMatrix single(nt, nn, row, SymmetricBlockMatrix::Precision::single_entries);
  const SymmetricBlockMatrix full(nt, nn, row);
  EXPECT_EQ(single.precision(), SymmetricBlockMatrix::Precision::single_entries);
  EXPECT_EQ(single.num_blocks(), full.num_blocks());
  EXPECT_LT(single.memory_bytes(), 0.6 * full.memory_bytes());  // 28 against 52 bytes a block
  Eigen::SparseMatrix<double, Eigen::RowMajor> rounded = m;
  for (Eigen::Index k = 0; k < rounded.outerSize(); ++k)
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(rounded, k); it; ++it)
      it.valueRef() = static_cast<float>(it.value());
  const Eigen::VectorXd f = Eigen::VectorXd::Random(3 * nn);
  const Eigen::VectorXd expected = rounded * f;
  EXPECT_LT((single * f - expected).norm(), 1e-14 * expected.norm());
  const Eigen::VectorXd magnitudes = m.cwiseAbs() * f.cwiseAbs();
  const Eigen::VectorXd moved = (single * f - m * f).cwiseAbs();
  for (Eigen::Index i = 0; i < moved.size(); ++i) EXPECT_LE(moved[i], 0x1p-24 * magnitudes[i] + 1e-15 * magnitudes[i]);
  EXPECT_GT((single * f - full * f).norm(), 0.0);  // rounded indeed
}

TEST(SymmetricBlockMatrix, RejectsWhatItCannotHold) {
  Eigen::SparseMatrix<double, Eigen::RowMajor> m = random_symmetric_blocks(4, 5, 7);
  EXPECT_THROW(SymmetricBlockMatrix(Eigen::SparseMatrix<double, Eigen::RowMajor>(7, 6)), std::invalid_argument);
  const SymmetricBlockMatrix b(m);
  EXPECT_THROW(b * Eigen::VectorXd::Zero(14), std::invalid_argument);
  m.coeffRef(0, 1) += 1e-6;  // block (0, 0) no longer symmetric
  EXPECT_THROW(SymmetricBlockMatrix{m}, std::invalid_argument);
}
