#pragma once
// Node data split over the ranks, for GMRES on vectors that each rank holds only a part of.
//
// Stacked node data (rows of 3 values, cell by cell) split by the cells' owners (ownership.h,
// or any blocks of the cells in order): rank r holds the rows of the cells it owns. The GMRES of (10) keeps its
// vectors this way (stepper/cell_velocity.h): each rank only its cells' rows, so the Krylov
// basis is split over the ranks, and a product's sum over the ranks reaches each rank only as
// its rows (only the rows of the other ranks' parts that are not zero travel) instead of whole
// on every rank.
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "libsolver/parallel/ownership.h"

namespace rbcflow {

class OwnedRows {
 public:
  OwnedRows(int cells, int nodes_per_cell, const Communicator& ranks);
  // Rank r holds the rows of cells first_cell[r] .. first_cell[r + 1] - 1 (ranks + 1 entries).
  OwnedRows(const std::vector<int>& first_cell, int nodes_per_cell, const Communicator& ranks);

  int rows() const { return mine_.size(); }  // this rank's
  int total_rows() const { return total_; }
  // This rank's rows of `all` (total_rows() x 3).
  Eigen::MatrixXd mine(const Eigen::MatrixXd& all) const;
  // The sum over the ranks of their `part`s (each total_rows() x 3), this rank's rows of it.
  // Only the rows of a part that are not zero travel to their owner (a rank's part of a layer
  // product is zero away from its cells and its slab of the grid).
  Eigen::MatrixXd sum_mine(const Eigen::MatrixXd& part) const;
  // Every rank's rows (`mine` on each, rows() x 3) stacked in order, on every rank.
  Eigen::MatrixXd gather(const Eigen::MatrixXd& mine) const;

  // The rows of the whole this rank reads (`needed`, ascending; its own may be among them):
  // after this, gather_read brings only those. Collective.
  void read_only(const std::vector<int>& needed);
  // The stacked rows (total_rows() x 3) with this rank's own rows and those of read_only's
  // (all of them before read_only), zero elsewhere. Collective.
  Eigen::MatrixXd gather_read(const Eigen::MatrixXd& mine) const;
  // Rows this rank has received from the others in gather_read and sum_mine so far.
  long rows_received() const { return rows_received_; }

  // The held layout: the rows of `cells` (ascending positions in the cells' order, this rank's
  // own among them, and those of read_only's rows), stacked in that order, as a rank's layers
  // hold them (CellLayers::held_cells). Not collective.
  void hold(std::vector<int> cells);
  Eigen::Index held_rows() const { return static_cast<Eigen::Index>(held_.size()) * nodes_per_cell_; }
  // gather_read into the held layout (held_rows() x 3): this rank's rows and read_only's, zero
  // at the other held rows; no matrix of every row on the way. Collective.
  Eigen::MatrixXd gather_read_held(const Eigen::MatrixXd& mine) const;
  // sum_mine of parts given in the held layout (each rank its own, held_rows() x 3): the same
  // rows travel, added in the same order, so the same bits as sum_mine of the parts at every row.
  Eigen::MatrixXd sum_mine_held(const Eigen::MatrixXd& part) const;

 private:
  int owner_of_row(int i) const;
  // Row i's row in the held layout, or -1 when its cell is not held.
  Eigen::Index held_row(int i) const;
  void check_read_rows_held() const;

  Communicator ranks_;
  int total_ = 0;
  int nodes_per_cell_ = 0;
  std::vector<int> held_;              // hold()'s cells, ascending
  Eigen::Index held_own_ = 0;          // the first own row in the held layout
  OwnedRange mine_;                    // rows
  std::vector<OwnedRange> blocks_;     // every rank's rows
  std::vector<int> counts_;            // every rank's values: 3 per row
  bool read_all_ = true;               // until read_only
  std::vector<std::vector<int>> send_rows_, read_rows_;  // by rank: own rows it reads, its rows read here
  mutable long rows_received_ = 0;
};

// Node vectors interleaved (x0 y0 z0 x1 ...: wall_elements.h's to_vector) split over the ranks
// by segments of the nodes: the wall solve's GMRES vectors (wall/wall_solver.h), each rank
// holding the nodes whose rows of the assembled operator it holds (wall_operator.h). The nodes
// are taken in an `order` (a permutation; by default their own) and cut into the ranks'
// segments in rank order; a segment lists its nodes in that order.
class OwnedSegments {
 public:
  // Blocks of the nodes in their own order (owned_block).
  OwnedSegments(int nodes, const Communicator& ranks);
  // Rank r's segment: order[first[r]] .. order[first[r + 1] - 1]; first has ranks + 1 entries
  // from 0 to the number of nodes.
  OwnedSegments(std::vector<int> order, const std::vector<int>& first, const Communicator& ranks);

  int size() const { return end_ - begin_; }  // this rank's nodes
  int total() const { return total_; }
  int node(int k) const { return order_.empty() ? begin_ + k : order_[begin_ + k]; }  // k-th of this rank's
  // The position of `node` in this rank's segment, or -1 when another rank owns it.
  int position(int node) const;
  bool operator==(const OwnedSegments& o) const;

  // This rank's segment of `all` (3 values a node, every node).
  Eigen::VectorXd mine(const Eigen::VectorXd& all) const;
  // The sum over the ranks of their `part`s (every node each), this rank's segment of it.
  // Only the nodes of a part that are not zero travel to their owner (a rank's part of a wall
  // product is zero away from its rows and its slab of the grid).
  Eigen::VectorXd sum_mine(const Eigen::VectorXd& part) const;
  // Every rank's segment (`mine` on each) in place, on every rank.
  Eigen::VectorXd gather(const Eigen::VectorXd& mine) const;

  // The nodes this rank reads (`needed`, ascending; its own may be among them): after this,
  // gather_read brings only those. Collective.
  void read_only(const std::vector<int>& needed);
  // A vector of every node with this rank's segment and the nodes of read_only's (all of them
  // before read_only), zero elsewhere. Collective.
  Eigen::VectorXd gather_read(const Eigen::VectorXd& mine) const;
  // Nodes this rank has received from the others in gather_read and sum_mine so far.
  long nodes_received() const { return nodes_received_; }

 private:
  // A vector in the segments' order (every node) back in the nodes' own order.
  Eigen::VectorXd unordered(const Eigen::VectorXd& in_order) const;

  Communicator ranks_;
  int total_ = 0;               // nodes
  int begin_ = 0, end_ = 0;     // this rank's positions in the order
  std::vector<int> order_;      // empty: the nodes' own
  std::vector<int> place_;      // place_[node]: its position in the order (with order_)
  std::vector<int> counts_;     // every rank's values: 3 per node
  bool read_all_ = true;        // until read_only
  std::vector<std::vector<int>> send_nodes_, read_nodes_;  // by rank: own nodes it reads, its nodes read here
  mutable long nodes_received_ = 0;
};

// GMRES's inner products (linear/preconditioned_gmres.h) of vectors split by rows over the
// ranks: each the sum of the ranks' parts, formed by Communicator::sum, so that every rank
// holds the same bits and takes the same iterations.
struct SplitInnerProducts {
  Communicator ranks;
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
    Eigen::VectorXd d(1);
    d[0] = a.dot(b);
    ranks.sum(d);
    return d[0];
  }
  double norm(const Eigen::VectorXd& a) const {
    Eigen::VectorXd s(1);
    s[0] = a.squaredNorm();
    ranks.sum(s);
    return std::sqrt(s[0]);
  }
  void sum(Eigen::VectorXd& partial) const { ranks.sum(partial); }
  bool all(bool here) const {
    Eigen::VectorXd not_here(1);
    not_here[0] = here ? 0.0 : 1.0;
    ranks.sum(not_here);
    return not_here[0] == 0.0;
  }
};

}  // namespace rbcflow
