#include "symmetric_block_matrix.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rbcflow {

SymmetricBlockMatrix::SymmetricBlockMatrix(const Eigen::SparseMatrix<double, Eigen::RowMajor>& m)
    : num_nodes_(static_cast<int>(m.cols() / 3)) {
  if (m.rows() % 3 != 0 || m.cols() % 3 != 0)
    throw std::invalid_argument("SymmetricBlockMatrix: the matrix is " + std::to_string(m.rows()) + " x " +
                                std::to_string(m.cols()) + ", not made of 3x3 blocks");
  const int nt = static_cast<int>(m.rows() / 3);
  // The blocks of each target, in ascending node order (rows are sorted by column).
  std::vector<std::vector<std::pair<int, Eigen::Matrix3d>>> rows(nt);
  bool symmetric = true;
#pragma omp parallel
  {
    std::vector<int> slot(num_nodes_, -1);
#pragma omp for schedule(dynamic, 64) reduction(&& : symmetric)
    for (int t = 0; t < nt; ++t) {
      std::vector<std::pair<int, Eigen::Matrix3d>>& row = rows[t];
      for (int k = 0; k < 3; ++k) {
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(m, 3 * t + k); it; ++it) {
          const int node = static_cast<int>(it.col() / 3);
          if (slot[node] < 0) {
            slot[node] = static_cast<int>(row.size());
            row.emplace_back(node, Eigen::Matrix3d::Zero());
          }
          row[slot[node]].second(k, it.col() % 3) = it.value();
        }
      }
      std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
      for (const auto& [node, b] : row) {
        slot[node] = -1;
        if ((b - b.transpose()).cwiseAbs().maxCoeff() > 1e-12 * b.cwiseAbs().maxCoeff()) symmetric = false;
      }
    }
  }
  if (!symmetric) throw std::invalid_argument("SymmetricBlockMatrix: a 3x3 block is not symmetric");
  offsets_.assign(nt + 1, 0);
  for (int t = 0; t < nt; ++t) offsets_[t + 1] = offsets_[t] + static_cast<std::int64_t>(rows[t].size());
  nodes_.resize(offsets_.back());
  blocks_.resize(offsets_.back());
#pragma omp parallel for schedule(static)
  for (int t = 0; t < nt; ++t) {
    std::int64_t i = offsets_[t];
    for (const auto& [node, b] : rows[t]) {
      nodes_[i] = node;
      blocks_[i++] = {b(0, 0), b(0, 1), b(0, 2), b(1, 1), b(1, 2), b(2, 2)};
    }
    std::vector<std::pair<int, Eigen::Matrix3d>>().swap(rows[t]);
  }
}

Eigen::VectorXd SymmetricBlockMatrix::operator*(const Eigen::VectorXd& f) const {
  if (f.size() != 3 * static_cast<Eigen::Index>(num_nodes_))
    throw std::invalid_argument("SymmetricBlockMatrix: " + std::to_string(f.size()) + " values for " +
                                std::to_string(num_nodes_) + " nodes");
  Eigen::VectorXd y(3 * static_cast<Eigen::Index>(num_targets()));
  const double* x = f.data();
#pragma omp parallel for schedule(static)
  for (int t = 0; t < num_targets(); ++t) {
    double y0 = 0.0, y1 = 0.0, y2 = 0.0;
    for (std::int64_t i = offsets_[t]; i < offsets_[t + 1]; ++i) {
      const std::array<double, 6>& b = blocks_[i];
      const double* v = x + 3 * static_cast<std::size_t>(nodes_[i]);
      y0 += b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
      y1 += b[1] * v[0] + b[3] * v[1] + b[4] * v[2];
      y2 += b[2] * v[0] + b[4] * v[1] + b[5] * v[2];
    }
    y[3 * t] = y0;
    y[3 * t + 1] = y1;
    y[3 * t + 2] = y2;
  }
  return y;
}

}  // namespace rbcflow
