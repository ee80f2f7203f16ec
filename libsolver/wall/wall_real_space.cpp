#include "wall_real_space.h"

#include <omp.h>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <vector>

#include "libsolver/kernels/ewald_real_kernel.h"
#include "triangle_rules.h"

namespace rbcflow {

namespace {

// One thread's accumulators over the wall nodes.
struct RowScratch {
  std::vector<Eigen::Matrix3d> blocks;
  std::vector<char> seen;
  std::vector<int> touched;
};

// Target t's blocks, emit(node, block) in ascending node order: the real-space sum over its
// Gauss-point neighbours, plus the entries of `plus` (rows 3t .. 3t+2) when given.
template <class Emit>
void real_space_row(const WallElements& e, const NeighborList& pairs, const EwaldRealKernel& kernel,
                    const Eigen::SparseMatrix<double, Eigen::RowMajor>* plus, int t, RowScratch& s, Emit&& emit) {
  if (s.blocks.empty()) {
    s.blocks.assign(e.num_nodes(), Eigen::Matrix3d::Zero());
    s.seen.assign(e.num_nodes(), 0);
  }
  const TriangleRule& rule = gauss7_rule();
  const std::vector<int>& order = pairs.order();
  auto touch = [&](int node) {
    if (!s.seen[node]) {
      s.seen[node] = 1;
      s.touched.push_back(node);
    }
  };
  pairs.for_each_neighbor(t, [&](int source, const Eigen::Vector3d& r) {
    const int q = order[source], triangle = q / 7, point = q % 7;
    const Eigen::Matrix3d g = e.weights[q] * kernel.stokeslet_matrix(r);
    for (int a = 0; a < 3; ++a) {
      const int node = e.wall.surface.triangles(triangle, a);
      touch(node);
      s.blocks[node] += rule.barycentric(point, a) * g;
    }
  });
  if (plus) {
    for (int k = 0; k < 3; ++k) {
      for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(*plus, 3 * t + k); it; ++it) {
        const int node = static_cast<int>(it.col() / 3);
        touch(node);
        s.blocks[node](k, it.col() % 3) += it.value();
      }
    }
  }
  std::sort(s.touched.begin(), s.touched.end());
  for (const int node : s.touched) {
    emit(node, s.blocks[node]);
    s.blocks[node].setZero();
    s.seen[node] = 0;
  }
  s.touched.clear();
}

}  // namespace

Eigen::SparseMatrix<double> wall_real_space_matrix(const WallElements& e, const NeighborList& pairs, double xi) {
  using Triplet = Eigen::Triplet<double>;
  const EwaldRealKernel kernel(xi);
  const int nt = pairs.n_targets();
  std::vector<std::vector<Triplet>> parts(omp_get_max_threads());
#pragma omp parallel
  {
    RowScratch scratch;
    std::vector<Triplet>& out = parts[omp_get_thread_num()];
#pragma omp for schedule(dynamic, 16)
    for (int t = 0; t < nt; ++t) {
      real_space_row(e, pairs, kernel, nullptr, t, scratch, [&](int node, const Eigen::Matrix3d& b) {
        for (int k = 0; k < 3; ++k)
          for (int l = 0; l < 3; ++l) out.emplace_back(3 * t + k, 3 * node + l, b(k, l));
      });
    }
  }
  std::vector<Triplet> all;
  for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  Eigen::SparseMatrix<double> m(3 * nt, 3 * e.num_nodes());
  m.setFromTriplets(all.begin(), all.end());
  return m;
}

namespace {

SymmetricBlockMatrix real_space_blocks(const WallElements& e, const NeighborList& pairs, double xi,
                                       const Eigen::SparseMatrix<double, Eigen::RowMajor>& plus,
                                       const std::function<bool(int)>& mine, SymmetricBlockMatrix::Precision precision) {
  if (plus.rows() != 3 * static_cast<Eigen::Index>(pairs.n_targets()) || plus.cols() != 3 * e.num_nodes())
    throw std::invalid_argument("wall_real_space_blocks: the added matrix must be 3 targets x 3 nodes");
  const EwaldRealKernel kernel(xi);
  std::vector<RowScratch> scratch(omp_get_max_threads());
  return SymmetricBlockMatrix(pairs.n_targets(), e.num_nodes(), [&](int t, SymmetricBlockMatrix::Row& row) {
    if (!mine(t)) return;
    real_space_row(e, pairs, kernel, &plus, t, scratch[omp_get_thread_num()],
                   [&](int node, const Eigen::Matrix3d& b) { row.emplace_back(node, b); });
  }, precision);
}

}  // namespace

SymmetricBlockMatrix wall_real_space_blocks(const WallElements& e, const NeighborList& pairs, double xi,
                                            const Eigen::SparseMatrix<double, Eigen::RowMajor>& plus, OwnedRange rows,
                                            SymmetricBlockMatrix::Precision precision) {
  return real_space_blocks(e, pairs, xi, plus, [&](int t) { return rows.contains(t); }, precision);
}

SymmetricBlockMatrix wall_real_space_blocks(const WallElements& e, const NeighborList& pairs, double xi,
                                            const Eigen::SparseMatrix<double, Eigen::RowMajor>& plus,
                                            const OwnedSegments& rows, SymmetricBlockMatrix::Precision precision) {
  if (rows.total() != pairs.n_targets())
    throw std::invalid_argument("wall_real_space_blocks: the segments are not of the targets");
  return real_space_blocks(e, pairs, xi, plus, [&](int t) { return rows.position(t) >= 0; }, precision);
}

}  // namespace rbcflow
