#include "symmetric_block_matrix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "libsolver/common/memory_report.h"

namespace rbcflow {

SymmetricBlockMatrix::SymmetricBlockMatrix(const Eigen::SparseMatrix<double, Eigen::RowMajor>& m)
    : SymmetricBlockMatrix(static_cast<int>(m.rows() / 3), static_cast<int>(m.cols() / 3), [&m](int t, Row& row) {
        std::vector<int> slot;  // the row's few nodes: a linear search is enough
        for (int k = 0; k < 3; ++k) {
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(m, 3 * t + k); it; ++it) {
            const int node = static_cast<int>(it.col() / 3);
            auto found = std::find(slot.begin(), slot.end(), node);
            if (found == slot.end()) {
              slot.push_back(node);
              row.emplace_back(node, Eigen::Matrix3d::Zero());
              found = slot.end() - 1;
            }
            row[found - slot.begin()].second(k, it.col() % 3) = it.value();
          }
        }
      }) {
  if (m.rows() % 3 != 0 || m.cols() % 3 != 0)
    throw std::invalid_argument("SymmetricBlockMatrix: the matrix is " + std::to_string(m.rows()) + " x " +
                                std::to_string(m.cols()) + ", not made of 3x3 blocks");
}

SymmetricBlockMatrix::SymmetricBlockMatrix(int num_targets, int num_nodes, const std::function<void(int, Row&)>& row,
                                           Precision precision)
    : num_nodes_(num_nodes), precision_(precision) {
  const int nt = num_targets;
  // Each target's blocks, sorted by node and packed at once (the unpacked rows of all targets
  // would take 1.5 times the matrix).
  std::vector<std::vector<std::pair<int, std::array<double, 6>>>> rows(nt);
  bool symmetric = true;
#pragma omp parallel
  {
    Row blocks;
#pragma omp for schedule(dynamic, 64) reduction(&& : symmetric)
    for (int t = 0; t < nt; ++t) {
      blocks.clear();
      row(t, blocks);
      std::sort(blocks.begin(), blocks.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      std::vector<std::pair<int, std::array<double, 6>>>& packed = rows[t];
      packed.reserve(blocks.size());
      // Against the row's largest entry: a block that is the small difference of two large
      // symmetric terms (a near-field correction beyond the real-space cutoff: accurate minus
      // Gauss-7 integrals of G, cancelling to ~1e-4 of either) keeps their rounding, far above
      // 1e-12 of itself; a kernel that is not symmetric shows in the row's large blocks.
      double row_scale = 0.0;
      for (const auto& [node, b] : blocks) row_scale = std::max(row_scale, b.cwiseAbs().maxCoeff());
      for (const auto& [node, b] : blocks) {
        if ((b - b.transpose()).cwiseAbs().maxCoeff() > 1e-12 * row_scale) symmetric = false;
        packed.emplace_back(node, std::array<double, 6>{b(0, 0), b(0, 1), b(0, 2), b(1, 1), b(1, 2), b(2, 2)});
      }
    }
  }
  if (!symmetric) throw std::invalid_argument("SymmetricBlockMatrix: a 3x3 block is not symmetric");
  offsets_.assign(nt + 1, 0);
  for (int t = 0; t < nt; ++t) offsets_[t + 1] = offsets_[t] + static_cast<std::int64_t>(rows[t].size());
  const bool single = precision == Precision::single_entries;
  nodes_.resize(offsets_.back());
  if (single) {
    single_.resize(offsets_.back());
  } else {
    blocks_.resize(offsets_.back());
  }
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) {
    std::int64_t i = offsets_[t];
    for (const auto& [node, b] : rows[t]) {
      nodes_[i] = node;
      if (single) {
        for (int k = 0; k < 6; ++k) single_[i][k] = static_cast<float>(b[k]);
      } else {
        blocks_[i] = b;
      }
      ++i;
    }
    std::vector<std::pair<int, std::array<double, 6>>>().swap(rows[t]);
  }
}

namespace {

// y = B f over the blocks of each target; the entries are read in their stored precision and
// the sums kept in double.
template <typename Scalar>
void block_product(const std::vector<std::int64_t>& offsets, const std::vector<int>& nodes,
                   const std::vector<std::array<Scalar, 6>>& blocks, const double* x, Eigen::VectorXd& y) {
  const int nt = static_cast<int>(offsets.size()) - 1;
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) {
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (std::int64_t i = offsets[t]; i < offsets[t + 1]; ++i) {
      const std::array<Scalar, 6>& s = blocks[i];
      const double b0 = s[0], b1 = s[1], b2 = s[2], b3 = s[3], b4 = s[4], b5 = s[5];
      const double* v = x + 3 * static_cast<std::size_t>(nodes[i]);
      y0 += b0 * v[0] + b1 * v[1] + b2 * v[2];
      y1 += b1 * v[0] + b3 * v[1] + b4 * v[2];
      y2 += b2 * v[0] + b4 * v[1] + b5 * v[2];
    }
    y[3 * t] = y0;
    y[3 * t + 1] = y1;
    y[3 * t + 2] = y2;
  }
}

}  // namespace

Eigen::VectorXd SymmetricBlockMatrix::operator*(const Eigen::VectorXd& f) const {
  if (f.size() != 3 * static_cast<Eigen::Index>(num_nodes_))
    throw std::invalid_argument("SymmetricBlockMatrix: " + std::to_string(f.size()) + " values for " +
                                std::to_string(num_nodes_) + " nodes");
  Eigen::VectorXd y(3 * static_cast<Eigen::Index>(num_targets()));
  if (precision_ == Precision::single_entries) {
    block_product(offsets_, nodes_, single_, f.data(), y);
  } else {
    block_product(offsets_, nodes_, blocks_, f.data(), y);
  }
  return y;
}

std::vector<int> SymmetricBlockMatrix::nodes_read() const {
  std::vector<int> nodes = nodes_;
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

std::size_t SymmetricBlockMatrix::memory_bytes() const {
  return heap_bytes(offsets_) + heap_bytes(nodes_) + heap_bytes(blocks_) + heap_bytes(single_);
}

}  // namespace rbcflow
