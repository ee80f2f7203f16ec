#pragma once
// The preconditioner of the wall solve (12) (wall_solver.h): sparse LUs of the near field's
// local part (NearField::local: the accurate integrals over each node's own star and a few
// more triangles), block-Jacobi over blocks of the wall nodes. A block is a slab of the wall
// across its longest extent, of about `block_nodes` nodes (the nodes sorted along that
// direction, ties by index, cut into equal runs); the couplings of the local part between
// blocks are left out. A wall of at most `block_nodes` nodes is one block: the LU of the whole
// local part. The blocks depend on the wall alone, not on the ranks, so the preconditioner
// and a solve's iterations are the same on any number of ranks; each rank factorises and
// applies only its blocks (owned_block of the blocks), which splits the preconditioner's
// memory and work over the ranks. The fill of a sparse LU grows faster than its size, so
// smaller blocks hold less in all, at the price of more GMRES iterations (bench/bench_wall.cpp,
// WallBlocks).
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <cstddef>
#include <memory>
#include <vector>

#include "libsolver/parallel/communicator.h"
#include "libsolver/parallel/owned_rows.h"

namespace rbcflow {

class WallPreconditioner {
 public:
  // `local`: 3 n x 3 n (index 3 i + k) for the n rows of `nodes`. block_nodes >= 1.
  // Throws std::runtime_error when a block's LU is singular.
  WallPreconditioner(const Eigen::SparseMatrix<double>& local, const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes,
                     int block_nodes, const Communicator& ranks);

  // This rank's segment of M^{-1} r, for r at every node (3 values a node, interleaved): the
  // ranks' blocks' solutions summed into the owners' segments (each value comes from one
  // block, so the sum adds zeros: the same bits on any number of ranks).
  Eigen::VectorXd solve_mine(const Eigen::VectorXd& r, const OwnedSegments& segments) const;
  // Whether every rank's segment holds exactly its blocks' nodes (wall_node_segments): then
  // solve_segment needs no other rank. Collective.
  bool matches(const OwnedSegments& segments) const;
  // M^{-1} r for r and the result this rank's segment, for segments that match().
  Eigen::VectorXd solve_segment(const Eigen::VectorXd& r, const OwnedSegments& segments) const;

  int blocks() const { return blocks_; }
  // L and U of this rank's blocks: a value and an index per nonzero.
  std::size_t bytes() const;

 private:
  struct Block {
    std::vector<int> nodes;  // ascending
    Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  };
  int nodes_ = 0;
  int blocks_ = 0;
  std::vector<std::unique_ptr<Block>> mine_;  // this rank's blocks
  Communicator ranks_;
};

// The blocks of n nodes: one when n <= block_nodes, else ceil(n / block_nodes).
int wall_preconditioner_blocks(long nodes, int block_nodes);

// The wall nodes in the preconditioner's slab order (along the longest extent of their bounding
// box, ties by index), and where each block starts in it (blocks + 1 entries, the last n).
struct WallSlabs {
  std::vector<int> order;
  std::vector<int> first;
};
WallSlabs wall_slabs(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes, int block_nodes);

// The wall solve's node segments that match the preconditioner of `block_nodes`: each rank's
// segment the nodes of its run of blocks (owned_block of the blocks), in slab order. Its
// preconditioner then reads and writes only its own segment, and its rows of the assembled
// operator are a slab of the wall. One rank: the nodes in their own order (one process's
// vectors, bit for bit). A rank owns no nodes when there are fewer blocks than ranks.
OwnedSegments wall_node_segments(const Eigen::Matrix<double, Eigen::Dynamic, 3>& nodes, int block_nodes,
                                 const Communicator& ranks);

}  // namespace rbcflow
