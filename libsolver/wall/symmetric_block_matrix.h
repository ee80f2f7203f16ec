#pragma once
// A sparse matrix of 3x3 blocks, targets by wall nodes, whose blocks are symmetric: sums of
// Stokeslets times scalars, as the wall operator's assembled real-space part and its near-field
// correction are (wall_real_space.h, near_field.h). Each block keeps the 6 entries of its upper
// triangle and one node index: 52 bytes against 108 for its 9 entries with their indices in a
// scalar sparse matrix, 28 with the entries rounded to single precision (Precision::single; the
// rounding keeps the blocks symmetric, and the products sum in double). Its product reads the
// matrix once and is bound by memory bandwidth, so it takes about half the time (bench_wall
// WallProduct).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

namespace rbcflow {

class SymmetricBlockMatrix {
 public:
  enum class Precision { double_entries, single_entries };

  // From a 3 n_targets x 3 n_nodes matrix (index 3 i + k). Throws std::invalid_argument when a
  // block differs from its transpose by more than 1e-12 of the largest entry of its row (the
  // upper triangle is kept: what is below it at rounding is dropped).
  explicit SymmetricBlockMatrix(const Eigen::SparseMatrix<double, Eigen::RowMajor>& m);
  // Row by row, without a scalar matrix in between (a tenth of its memory at the peak):
  // row(t, blocks) appends target t's blocks, one per node, in any order; it is called from
  // several OpenMP threads at once (for different t). Same checks, made before the rounding.
  using Row = std::vector<std::pair<int, Eigen::Matrix3d>>;
  SymmetricBlockMatrix(int num_targets, int num_nodes, const std::function<void(int, Row&)>& row,
                       Precision precision = Precision::double_entries);

  int num_targets() const { return static_cast<int>(offsets_.size()) - 1; }
  int num_nodes() const { return num_nodes_; }
  std::int64_t num_blocks() const { return offsets_.back(); }
  std::size_t memory_bytes() const;
  Precision precision() const { return precision_; }

  // The product with nodal values (index 3 i + k); one value per target row.
  Eigen::VectorXd operator*(const Eigen::VectorXd& f) const;
  // The nodes the product reads (those of some block), ascending.
  std::vector<int> nodes_read() const;

 private:
  int num_nodes_;
  std::vector<std::int64_t> offsets_;  // blocks of target t: [offsets_[t], offsets_[t + 1])
  std::vector<int> nodes_;
  Precision precision_ = Precision::double_entries;
  std::vector<std::array<double, 6>> blocks_;  // xx, xy, xz, yy, yz, zz; or
  std::vector<std::array<float, 6>> single_;   // the same rounded (Precision::single_entries)
};

}  // namespace rbcflow
