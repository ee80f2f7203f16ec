#include "owned_rows.h"

#include <stdexcept>

namespace rbcflow {

OwnedRows::OwnedRows(int cells, int nodes_per_cell, const Communicator& ranks)
    : ranks_(ranks), total_(cells * nodes_per_cell) {
  for (int r = 0; r < ranks.size(); ++r) {
    const OwnedRange c = owned_block(cells, r, ranks.size());
    blocks_.push_back({c.begin * nodes_per_cell, c.end * nodes_per_cell});
    counts_.push_back(3 * blocks_.back().size());
  }
  mine_ = blocks_[static_cast<std::size_t>(ranks.rank())];
}

Eigen::MatrixXd OwnedRows::mine(const Eigen::MatrixXd& all) const {
  if (all.rows() != total_ || all.cols() != 3) throw std::invalid_argument("OwnedRows::mine: not stacked node data of the cells");
  return all.middleRows(mine_.begin, mine_.size());
}

Eigen::MatrixXd OwnedRows::sum_mine(const Eigen::MatrixXd& part) const {
  if (part.rows() != total_ || part.cols() != 3) throw std::invalid_argument("OwnedRows::sum_mine: not stacked node data of the cells");
  // The ranks' pieces one after the other, each its rows x 3 in column order.
  Eigen::VectorXd pieces(3 * static_cast<Eigen::Index>(total_));
  for (const OwnedRange& b : blocks_)
    Eigen::Map<Eigen::MatrixXd>(pieces.data() + 3 * static_cast<Eigen::Index>(b.begin), b.size(), 3) =
        part.middleRows(b.begin, b.size());
  Eigen::MatrixXd sum(mine_.size(), 3);
  ranks_.sum_pieces({pieces.data(), static_cast<std::size_t>(pieces.size())}, {sum.data(), static_cast<std::size_t>(sum.size())},
                    counts_);
  return sum;
}

Eigen::MatrixXd OwnedRows::gather(const Eigen::MatrixXd& mine) const {
  if (mine.rows() != mine_.size() || mine.cols() != 3) throw std::invalid_argument("OwnedRows::gather: not this rank's rows");
  Eigen::VectorXd pieces(3 * static_cast<Eigen::Index>(total_));
  ranks_.gather_pieces({mine.data(), static_cast<std::size_t>(mine.size())},
                       {pieces.data(), static_cast<std::size_t>(pieces.size())}, counts_);
  Eigen::MatrixXd all(total_, 3);
  for (const OwnedRange& b : blocks_)
    all.middleRows(b.begin, b.size()) =
        Eigen::Map<const Eigen::MatrixXd>(pieces.data() + 3 * static_cast<Eigen::Index>(b.begin), b.size(), 3);
  return all;
}

OwnedSegments::OwnedSegments(int nodes, const Communicator& ranks)
    : ranks_(ranks), total_(nodes), mine_(owned_block(nodes, ranks)) {
  for (int r = 0; r < ranks.size(); ++r) counts_.push_back(3 * owned_block(nodes, r, ranks.size()).size());
}

Eigen::VectorXd OwnedSegments::mine(const Eigen::VectorXd& all) const {
  if (all.size() != 3 * static_cast<Eigen::Index>(total_)) throw std::invalid_argument("OwnedSegments::mine: not a vector of every node");
  return all.segment(3 * mine_.begin, 3 * mine_.size());
}

Eigen::VectorXd OwnedSegments::sum_mine(const Eigen::VectorXd& part) const {
  if (part.size() != 3 * static_cast<Eigen::Index>(total_)) throw std::invalid_argument("OwnedSegments::sum_mine: not a vector of every node");
  Eigen::VectorXd sum(3 * mine_.size());
  ranks_.sum_pieces({part.data(), static_cast<std::size_t>(part.size())}, {sum.data(), static_cast<std::size_t>(sum.size())},
                    counts_);
  return sum;
}

Eigen::VectorXd OwnedSegments::gather(const Eigen::VectorXd& mine) const {
  if (mine.size() != 3 * mine_.size()) throw std::invalid_argument("OwnedSegments::gather: not this rank's segment");
  Eigen::VectorXd all(3 * static_cast<Eigen::Index>(total_));
  ranks_.gather_pieces({mine.data(), static_cast<std::size_t>(mine.size())}, {all.data(), static_cast<std::size_t>(all.size())},
                       counts_);
  return all;
}

}  // namespace rbcflow
