#include "wall_preconditioner.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "libsolver/parallel/ownership.h"

namespace rbcflow {

int wall_preconditioner_blocks(long nodes, int block_nodes) {
  if (block_nodes < 1) throw std::invalid_argument("wall preconditioner: block_nodes must be at least 1");
  return nodes <= block_nodes ? 1 : static_cast<int>((nodes + block_nodes - 1) / block_nodes);
}

WallSlabs wall_slabs(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes, int block_nodes) {
  const int n = static_cast<int>(nodes.rows());
  const int blocks = wall_preconditioner_blocks(n, block_nodes);
  WallSlabs s;
  s.order.resize(n);
  std::iota(s.order.begin(), s.order.end(), 0);
  if (blocks > 1) {
    Eigen::Index axis = 0;
    (nodes.colwise().maxCoeff() - nodes.colwise().minCoeff()).maxCoeff(&axis);
    std::stable_sort(s.order.begin(), s.order.end(), [&](int a, int b) { return nodes(a, axis) < nodes(b, axis); });
  }
  for (int b = 0; b < blocks; ++b) s.first.push_back(owned_block(n, b, blocks).begin);
  s.first.push_back(n);
  return s;
}

OwnedSegments wall_node_segments(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes, int block_nodes,
                                 const Communicator& ranks) {
  if (ranks.size() == 1) return OwnedSegments(static_cast<int>(nodes.rows()), ranks);
  WallSlabs s = wall_slabs(nodes, block_nodes);
  const int blocks = static_cast<int>(s.first.size()) - 1;
  std::vector<int> first;
  for (int r = 0; r < ranks.size(); ++r) first.push_back(s.first[owned_block(blocks, r, ranks.size()).begin]);
  first.push_back(static_cast<int>(nodes.rows()));
  return OwnedSegments(std::move(s.order), first, ranks);
}

namespace {

// block_of[i] for every node: the runs of wall_slabs.
std::vector<int> slab_blocks(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes, int block_nodes) {
  const WallSlabs s = wall_slabs(nodes, block_nodes);
  std::vector<int> block_of(nodes.rows(), 0);
  for (std::size_t b = 0; b + 1 < s.first.size(); ++b)
    for (int k = s.first[b]; k < s.first[b + 1]; ++k) block_of[s.order[k]] = static_cast<int>(b);
  return block_of;
}

}  // namespace

WallPreconditioner::WallPreconditioner(const Eigen::SparseMatrix<double>& local,
                                       const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes, int block_nodes,
                                       const Communicator& ranks)
    : nodes_(static_cast<int>(nodes.rows())), blocks_(wall_preconditioner_blocks(nodes.rows(), block_nodes)), ranks_(ranks) {
  if (local.rows() != 3 * nodes.rows() || local.cols() != 3 * nodes.rows())
    throw std::invalid_argument("wall preconditioner: the local near field is not 3 n x 3 n for the n nodes");
  const std::vector<int> block_of = slab_blocks(nodes, block_nodes);
  const OwnedRange owned = owned_block(blocks_, ranks);
  // Each node's index in its block, and this rank's blocks' node lists (ascending: the order
  // of the whole matrix, so that one block is the whole local part unchanged).
  std::vector<int> position(nodes_, -1);
  for (int b = owned.begin; b < owned.end; ++b) mine_.push_back(std::make_unique<Block>());
  for (int i = 0; i < nodes_; ++i) {
    if (!owned.contains(block_of[i])) continue;
    std::vector<int>& list = mine_[block_of[i] - owned.begin]->nodes;
    position[i] = static_cast<int>(list.size());
    list.push_back(i);
  }
  std::vector<std::vector<Eigen::Triplet<double>>> entries(mine_.size());
  for (int col = 0; col < local.outerSize(); ++col) {
    const int j = col / 3, b = block_of[j];
    if (!owned.contains(b)) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(local, col); it; ++it) {
      const int i = static_cast<int>(it.row()) / 3;
      if (block_of[i] != b) continue;  // a coupling between blocks: left out
      entries[b - owned.begin].emplace_back(3 * position[i] + it.row() % 3, 3 * position[j] + col % 3, it.value());
    }
  }
  for (std::size_t k = 0; k < mine_.size(); ++k) {
    Block& block = *mine_[k];
    const Eigen::Index size = 3 * static_cast<Eigen::Index>(block.nodes.size());
    Eigen::SparseMatrix<double> a(size, size);
    a.setFromTriplets(entries[k].begin(), entries[k].end());
    entries[k] = {};
    block.lu.compute(a);
    if (block.lu.info() != Eigen::Success)
      throw std::runtime_error("wall solver: the near-field preconditioner's block " + std::to_string(owned.begin + k) +
                               " of " + std::to_string(blocks_) + " is singular");
  }
}

Eigen::VectorXd WallPreconditioner::solve_mine(const Eigen::VectorXd& r, const OwnedSegments& segments) const {
  if (r.size() != 3 * static_cast<Eigen::Index>(nodes_))
    throw std::invalid_argument("wall preconditioner: not a vector of every node");
  Eigen::VectorXd z = Eigen::VectorXd::Zero(r.size());
#pragma omp parallel for schedule(dynamic) if (mine_.size() > 1)
  for (std::size_t k = 0; k < mine_.size(); ++k) {
    const Block& block = *mine_[k];
    Eigen::VectorXd rb(3 * block.nodes.size());
    for (std::size_t a = 0; a < block.nodes.size(); ++a) rb.segment<3>(3 * a) = r.segment<3>(3 * block.nodes[a]);
    const Eigen::VectorXd zb = block.lu.solve(rb);
    for (std::size_t a = 0; a < block.nodes.size(); ++a) z.segment<3>(3 * block.nodes[a]) = zb.segment<3>(3 * a);
  }
  return ranks_.size() == 1 ? z : segments.sum_mine(z);
}

bool WallPreconditioner::matches(const OwnedSegments& segments) const {
  bool here = segments.total() == nodes_;
  int held = 0;
  for (const auto& b : mine_) {
    held += static_cast<int>(b->nodes.size());
    for (int i : b->nodes) here = here && segments.position(i) >= 0;
  }
  here = here && held == segments.size();
  return SplitInnerProducts{ranks_}.all(here);
}

Eigen::VectorXd WallPreconditioner::solve_segment(const Eigen::VectorXd& r, const OwnedSegments& segments) const {
  if (r.size() != 3 * static_cast<Eigen::Index>(segments.size()))
    throw std::invalid_argument("wall preconditioner: not a vector of this rank's segment");
  Eigen::VectorXd z(r.size());
#pragma omp parallel for schedule(dynamic) if (mine_.size() > 1)
  for (std::size_t k = 0; k < mine_.size(); ++k) {
    const Block& block = *mine_[k];
    Eigen::VectorXd rb(3 * block.nodes.size());
    for (std::size_t a = 0; a < block.nodes.size(); ++a) rb.segment<3>(3 * a) = r.segment<3>(3 * segments.position(block.nodes[a]));
    const Eigen::VectorXd zb = block.lu.solve(rb);
    for (std::size_t a = 0; a < block.nodes.size(); ++a) z.segment<3>(3 * segments.position(block.nodes[a])) = zb.segment<3>(3 * a);
  }
  return z;
}

std::size_t WallPreconditioner::bytes() const {
  std::size_t sum = 0;
  for (const auto& b : mine_) sum += static_cast<std::size_t>(b->lu.nnzL() + b->lu.nnzU()) * (sizeof(double) + sizeof(int));
  return sum;
}

}  // namespace rbcflow
