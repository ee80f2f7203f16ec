#include "owned_rows.h"

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <utility>

namespace rbcflow {

namespace {

std::vector<int> block_firsts(int cells, int ranks) {
  std::vector<int> first;
  for (int r = 0; r < ranks; ++r) first.push_back(owned_block(cells, r, ranks).begin);
  first.push_back(cells);
  return first;
}

}  // namespace

OwnedRows::OwnedRows(int cells, int nodes_per_cell, const Communicator& ranks)
    : OwnedRows(block_firsts(cells, ranks.size()), nodes_per_cell, ranks) {}

OwnedRows::OwnedRows(const std::vector<int>& first_cell, int nodes_per_cell, const Communicator& ranks)
    : ranks_(ranks), nodes_per_cell_(nodes_per_cell) {
  const std::size_t p = static_cast<std::size_t>(ranks.size());
  bool valid = first_cell.size() == p + 1 && first_cell.front() == 0;
  for (std::size_t r = 0; valid && r < p; ++r) valid = first_cell[r] <= first_cell[r + 1];
  if (!valid) throw std::invalid_argument("OwnedRows: first cells must rise from 0, one a rank and one more");
  total_ = first_cell.back() * nodes_per_cell;
  for (std::size_t r = 0; r < p; ++r) {
    blocks_.push_back({first_cell[r] * nodes_per_cell, first_cell[r + 1] * nodes_per_cell});
    counts_.push_back(3 * blocks_.back().size());
  }
  mine_ = blocks_[static_cast<std::size_t>(ranks.rank())];
}

Eigen::MatrixXd OwnedRows::mine(const Eigen::MatrixXd& all) const {
  if (all.rows() != total_ || all.cols() != 3) throw std::invalid_argument("OwnedRows::mine: not stacked node data of the cells");
  return all.middleRows(mine_.begin, mine_.size());
}

namespace {

std::vector<int> values_per_rank(const std::vector<std::vector<int>>& rows, int per_row) {
  std::vector<int> counts;
  for (const std::vector<int>& of_rank : rows) counts.push_back(per_row * static_cast<int>(of_rank.size()));
  return counts;
}

// Each rank tells each owner which of its items (rows, nodes) it reads (`read`, by owner);
// returns, by rank, the items of this rank that the rank reads. Collective.
std::vector<std::vector<int>> items_read_by(const Communicator& ranks, const std::vector<std::vector<int>>& read) {
  const std::vector<int> counts = values_per_rank(read, 1);
  const std::vector<int> recv_counts = ranks.exchange_counts(counts);
  std::vector<int> out, in;
  for (const std::vector<int>& of_rank : read) out.insert(out.end(), of_rank.begin(), of_rank.end());
  long total = 0;
  for (int n : recv_counts) total += n;
  in.resize(static_cast<std::size_t>(total));
  ranks.exchange(out, counts, in, recv_counts);
  std::vector<std::vector<int>> send(static_cast<std::size_t>(ranks.size()));
  std::size_t k = 0;
  for (std::size_t r = 0; r < send.size(); ++r)
    for (int n = 0; n < recv_counts[r]; ++n) send[r].push_back(in[k++]);
  return send;
}

// Sends each rank the 3 values of each of its items in `send` (by rank) and receives those of
// each item in `read` (by owner), all through value(item, c) (a reference); returns the items
// received. Collective.
template <class Value>
long exchange_read(const Communicator& ranks, const std::vector<std::vector<int>>& send,
                   const std::vector<std::vector<int>>& read, Value&& value) {
  std::vector<double> out;
  for (const std::vector<int>& of_rank : send)
    for (int i : of_rank)
      for (int c = 0; c < 3; ++c) out.push_back(value(i, c));
  const std::vector<int> recv_counts = values_per_rank(read, 3);
  long received = 0;
  for (int n : recv_counts) received += n;
  std::vector<double> in(static_cast<std::size_t>(received));
  ranks.exchange(out, values_per_rank(send, 3), in, recv_counts);
  std::size_t k = 0;
  for (const std::vector<int>& of_rank : read)
    for (int i : of_rank)
      for (int c = 0; c < 3; ++c) value(i, c) = in[k++];
  return received / 3;
}

// Sends each rank r the items of send[r] (by rank) with their 3 values value(i, c), and adds
// each item received to add(i, c, v) in rank order: the same sum whatever order the messages
// came in. Returns the items received. Collective.
template <class Value, class Add>
long send_and_add(const Communicator& ranks, const std::vector<std::vector<int>>& send, Value&& value, Add&& add) {
  const std::vector<int> send_counts = values_per_rank(send, 1);
  const std::vector<int> recv_counts = ranks.exchange_counts(send_counts);
  std::vector<int> send_index;
  for (const std::vector<int>& of_rank : send) send_index.insert(send_index.end(), of_rank.begin(), of_rank.end());
  long received = 0;
  for (int n : recv_counts) received += n;
  std::vector<int> recv_index(static_cast<std::size_t>(received));
  ranks.exchange(send_index, send_counts, recv_index, recv_counts);
  std::vector<double> out;
  for (int i : send_index)
    for (int c = 0; c < 3; ++c) out.push_back(value(i, c));
  std::vector<int> recv_values(recv_counts);
  for (int& n : recv_values) n *= 3;
  std::vector<double> in(3 * static_cast<std::size_t>(received));
  ranks.exchange(out, values_per_rank(send, 3), in, recv_values);
  for (std::size_t k = 0; k < recv_index.size(); ++k)
    for (int c = 0; c < 3; ++c) add(recv_index[k], c, in[3 * k + static_cast<std::size_t>(c)]);
  return received;
}

}  // namespace

Eigen::MatrixXd OwnedRows::sum_mine(const Eigen::MatrixXd& part) const {
  if (part.rows() != total_ || part.cols() != 3) throw std::invalid_argument("OwnedRows::sum_mine: not stacked node data of the cells");
  Eigen::MatrixXd sum = part.middleRows(mine_.begin, mine_.size());
  const int p = ranks_.size();
  if (p == 1) return sum;
  // Each other rank's rows of this part that are not zero (a zero row adds nothing: exact).
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(p));
  for (int r = 0; r < p; ++r) {
    if (r == ranks_.rank()) continue;
    for (int i = blocks_[r].begin; i < blocks_[r].end; ++i)
      if (!part.row(i).isZero(0.0)) rows[r].push_back(i);
  }
  rows_received_ += send_and_add(ranks_, rows, [&](int i, int c) { return part(i, c); },
                                 [&](int i, int c, double v) { sum(i - mine_.begin, c) += v; });
  return sum;
}

void OwnedRows::read_only(const std::vector<int>& needed) {
  const int p = ranks_.size();
  if (!std::is_sorted(needed.begin(), needed.end()) || (!needed.empty() && (needed.front() < 0 || needed.back() >= total_)))
    throw std::invalid_argument("OwnedRows::read_only: the rows must be ascending rows of the whole");
  read_rows_.assign(static_cast<std::size_t>(p), {});
  for (int i : needed) {
    if (mine_.contains(i)) continue;
    const int r = owner_of_row(i);
    if (read_rows_[r].empty() || read_rows_[r].back() != i) read_rows_[r].push_back(i);
  }
  send_rows_ = items_read_by(ranks_, read_rows_);
  read_all_ = false;
  check_read_rows_held();
}

int OwnedRows::owner_of_row(int i) const {
  const auto after = std::upper_bound(blocks_.begin(), blocks_.end(), i,
                                      [](int row, const OwnedRange& b) { return row < b.end; });
  return static_cast<int>(after - blocks_.begin());
}

Eigen::Index OwnedRows::held_row(int i) const {
  const int c = i / nodes_per_cell_;
  const auto at = std::lower_bound(held_.begin(), held_.end(), c);
  if (at == held_.end() || *at != c) return -1;
  return static_cast<Eigen::Index>(at - held_.begin()) * nodes_per_cell_ + i % nodes_per_cell_;
}

void OwnedRows::check_read_rows_held() const {
  if (held_.empty() || read_all_) return;
  for (const std::vector<int>& of_rank : read_rows_)
    for (const int i : of_rank)
      if (held_row(i) < 0) throw std::invalid_argument("OwnedRows: a row read is not among the held cells' rows");
}

void OwnedRows::hold(std::vector<int> cells) {
  const int np = nodes_per_cell_;
  const bool ascending = std::adjacent_find(cells.begin(), cells.end(), std::greater_equal<>()) == cells.end();
  if (!ascending || (!cells.empty() && (cells.front() < 0 || cells.back() * np >= total_)))
    throw std::invalid_argument("OwnedRows::hold: the cells must be ascending positions of the cells");
  held_ = std::move(cells);
  if (mine_.empty()) {
    held_own_ = 0;
  } else {
    held_own_ = held_row(mine_.begin);
    if (held_own_ < 0 || held_row(mine_.end - 1) != held_own_ + mine_.size() - 1)
      throw std::invalid_argument("OwnedRows::hold: this rank's own cells must be among the held cells");
  }
  check_read_rows_held();
}

Eigen::MatrixXd OwnedRows::gather_read_held(const Eigen::MatrixXd& mine) const {
  if (mine.rows() != mine_.size() || mine.cols() != 3) throw std::invalid_argument("OwnedRows::gather_read: not this rank's rows");
  Eigen::MatrixXd held = Eigen::MatrixXd::Zero(held_rows(), 3);
  if (read_all_) {  // every held row from its owner
    const Eigen::MatrixXd all = gather(mine);
    for (std::size_t k = 0; k < held_.size(); ++k)
      held.middleRows(static_cast<Eigen::Index>(k) * nodes_per_cell_, nodes_per_cell_) =
          all.middleRows(static_cast<Eigen::Index>(held_[k]) * nodes_per_cell_, nodes_per_cell_);
    return held;
  }
  held.middleRows(held_own_, mine_.size()) = mine;
  if (ranks_.size() == 1) return held;
  rows_received_ += exchange_read(ranks_, send_rows_, read_rows_, [&](int i, int c) -> double& { return held(held_row(i), c); });
  return held;
}

Eigen::MatrixXd OwnedRows::sum_mine_held(const Eigen::MatrixXd& part) const {
  if (part.rows() != held_rows() || part.cols() != 3) throw std::invalid_argument("OwnedRows::sum_mine: not the held rows");
  Eigen::MatrixXd sum = part.middleRows(held_own_, mine_.size());
  const int p = ranks_.size(), np = nodes_per_cell_;
  if (p == 1) return sum;
  // As sum_mine: each other rank's rows that are not zero, ascending.
  std::vector<std::vector<int>> rows(static_cast<std::size_t>(p));
  for (std::size_t k = 0; k < held_.size(); ++k) {
    const int first = held_[k] * np, r = owner_of_row(first);
    if (r == ranks_.rank()) continue;
    for (int j = 0; j < np; ++j)
      if (!part.row(static_cast<Eigen::Index>(k) * np + j).isZero(0.0)) rows[r].push_back(first + j);
  }
  rows_received_ += send_and_add(ranks_, rows, [&](int i, int c) { return part(held_row(i), c); },
                                 [&](int i, int c, double v) { sum(i - mine_.begin, c) += v; });
  return sum;
}

Eigen::MatrixXd OwnedRows::gather_read(const Eigen::MatrixXd& mine) const {
  if (read_all_) return gather(mine);
  if (mine.rows() != mine_.size() || mine.cols() != 3) throw std::invalid_argument("OwnedRows::gather_read: not this rank's rows");
  Eigen::MatrixXd all = Eigen::MatrixXd::Zero(total_, 3);
  all.middleRows(mine_.begin, mine_.size()) = mine;
  if (ranks_.size() == 1) return all;
  rows_received_ += exchange_read(ranks_, send_rows_, read_rows_, [&](int i, int c) -> double& { return all(i, c); });
  return all;
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

OwnedSegments::OwnedSegments(int nodes, const Communicator& ranks) : ranks_(ranks), total_(nodes) {
  const OwnedRange mine = owned_block(nodes, ranks);
  begin_ = mine.begin;
  end_ = mine.end;
  for (int r = 0; r < ranks.size(); ++r) counts_.push_back(3 * owned_block(nodes, r, ranks.size()).size());
}

OwnedSegments::OwnedSegments(std::vector<int> order, const std::vector<int>& first, const Communicator& ranks)
    : ranks_(ranks), total_(static_cast<int>(order.size())), order_(std::move(order)), place_(total_, -1) {
  if (first.size() != static_cast<std::size_t>(ranks.size()) + 1 || first.front() != 0 || first.back() != total_)
    throw std::invalid_argument("OwnedSegments: the segments' first positions must run from 0 to the nodes, one per rank and one more");
  for (int k = 0; k < total_; ++k) {
    const int i = order_[k];
    if (i < 0 || i >= total_ || place_[i] >= 0) throw std::invalid_argument("OwnedSegments: the order is not a permutation of the nodes");
    place_[i] = k;
  }
  for (int r = 0; r < ranks.size(); ++r) {
    if (first[r + 1] < first[r]) throw std::invalid_argument("OwnedSegments: the segments' first positions must not decrease");
    counts_.push_back(3 * (first[r + 1] - first[r]));
  }
  begin_ = first[ranks.rank()];
  end_ = first[ranks.rank() + 1];
}

int OwnedSegments::position(int node) const {
  const int k = order_.empty() ? node : place_[node];
  return begin_ <= k && k < end_ ? k - begin_ : -1;
}

bool OwnedSegments::operator==(const OwnedSegments& o) const {
  return total_ == o.total_ && begin_ == o.begin_ && end_ == o.end_ && counts_ == o.counts_ && order_ == o.order_;
}

Eigen::VectorXd OwnedSegments::unordered(const Eigen::VectorXd& in_order) const {
  if (order_.empty()) return in_order;
  Eigen::VectorXd out(in_order.size());
  for (int k = 0; k < total_; ++k) out.segment<3>(3 * order_[k]) = in_order.segment<3>(3 * k);
  return out;
}

Eigen::VectorXd OwnedSegments::mine(const Eigen::VectorXd& all) const {
  if (all.size() != 3 * static_cast<Eigen::Index>(total_)) throw std::invalid_argument("OwnedSegments::mine: not a vector of every node");
  Eigen::VectorXd out(3 * size());
  for (int k = 0; k < size(); ++k) out.segment<3>(3 * k) = all.segment<3>(3 * node(k));
  return out;
}

Eigen::VectorXd OwnedSegments::sum_mine(const Eigen::VectorXd& part) const {
  if (part.size() != 3 * static_cast<Eigen::Index>(total_)) throw std::invalid_argument("OwnedSegments::sum_mine: not a vector of every node");
  Eigen::VectorXd sum = mine(part);
  const int p = ranks_.size();
  if (p == 1) return sum;
  // Each other rank's nodes of this part that are not zero (a zero node adds nothing: exact).
  std::vector<std::vector<int>> nodes(static_cast<std::size_t>(p));
  int k = 0;
  for (int r = 0; r < p; ++r)
    for (const int end = k + counts_[r] / 3; k < end; ++k) {
      const int i = order_.empty() ? k : order_[k];
      if (r != ranks_.rank() && !part.segment<3>(3 * static_cast<Eigen::Index>(i)).isZero(0.0)) nodes[r].push_back(i);
    }
  nodes_received_ += send_and_add(ranks_, nodes, [&](int i, int c) { return part[3 * static_cast<Eigen::Index>(i) + c]; },
                                  [&](int i, int c, double v) { sum[3 * static_cast<Eigen::Index>(position(i)) + c] += v; });
  return sum;
}

void OwnedSegments::read_only(const std::vector<int>& needed) {
  const int p = ranks_.size();
  if (!std::is_sorted(needed.begin(), needed.end()) || (!needed.empty() && (needed.front() < 0 || needed.back() >= total_)))
    throw std::invalid_argument("OwnedSegments::read_only: the nodes must be ascending nodes of the whole");
  std::vector<int> first{0};  // every rank's first position in the order
  for (int n : counts_) first.push_back(first.back() + n / 3);
  read_nodes_.assign(static_cast<std::size_t>(p), {});
  for (int i : needed) {
    const int k = order_.empty() ? i : place_[i];
    if (begin_ <= k && k < end_) continue;
    const auto r = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), k) - first.begin() - 1);
    if (read_nodes_[r].empty() || read_nodes_[r].back() != i) read_nodes_[r].push_back(i);
  }
  send_nodes_ = items_read_by(ranks_, read_nodes_);
  read_all_ = false;
}

Eigen::VectorXd OwnedSegments::gather_read(const Eigen::VectorXd& mine) const {
  if (read_all_) return gather(mine);
  if (mine.size() != 3 * size()) throw std::invalid_argument("OwnedSegments::gather_read: not this rank's segment");
  Eigen::VectorXd all = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(total_));
  for (int k = 0; k < size(); ++k) all.segment<3>(3 * static_cast<Eigen::Index>(node(k))) = mine.segment<3>(3 * k);
  if (ranks_.size() == 1) return all;
  nodes_received_ += exchange_read(ranks_, send_nodes_, read_nodes_,
                                   [&](int i, int c) -> double& { return all[3 * static_cast<Eigen::Index>(i) + c]; });
  return all;
}

Eigen::VectorXd OwnedSegments::gather(const Eigen::VectorXd& mine) const {
  if (mine.size() != 3 * size()) throw std::invalid_argument("OwnedSegments::gather: not this rank's segment");
  Eigen::VectorXd all(3 * static_cast<Eigen::Index>(total_));
  ranks_.gather_pieces({mine.data(), static_cast<std::size_t>(mine.size())}, {all.data(), static_cast<std::size_t>(all.size())},
                       counts_);
  return unordered(all);
}

}  // namespace rbcflow
