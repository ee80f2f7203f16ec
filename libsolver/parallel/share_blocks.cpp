#include "share_blocks.h"

#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>

#include "libsolver/parallel/ownership.h"

namespace rbcflow {

void share_blocks(const Communicator& ranks, const std::vector<std::vector<std::span<double>>>& items) {
  if (ranks.size() == 1) return;
  const int n = static_cast<int>(items.size());
  std::vector<std::size_t> offset(n + 1, 0);  // of item i in the packed values
  for (int i = 0; i < n; ++i) {
    offset[i + 1] = offset[i];
    for (const std::span<double>& a : items[i]) offset[i + 1] += a.size();
  }
  std::vector<int> counts;
  for (int r = 0; r < ranks.size(); ++r) {
    const OwnedRange b = owned_block(n, r, ranks.size());
    counts.push_back(static_cast<int>(offset[b.end] - offset[b.begin]));
  }
  const OwnedRange mine = owned_block(n, ranks);
  std::vector<double> own(offset[mine.end] - offset[mine.begin]), all(offset[n]);
  auto at = own.begin();
  for (int i = mine.begin; i < mine.end; ++i)
    for (const std::span<double>& a : items[i]) at = std::copy(a.begin(), a.end(), at);
  ranks.gather_pieces(own, all, counts);
  auto from = all.cbegin();
  for (const std::vector<std::span<double>>& item : items)
    for (const std::span<double>& a : item) {
      std::copy(from, from + static_cast<long>(a.size()), a.begin());
      from += static_cast<long>(a.size());
    }
}

int bring_items(const Communicator& ranks, const std::vector<int>& owner, const std::vector<int>& needed,
                const std::vector<std::vector<std::span<double>>>& items) {
  if (owner.size() != items.size()) throw std::invalid_argument("bring_items: one owner an item");
  if (ranks.size() == 1) return 0;
  const int p = ranks.size();
  const auto values_of = [&](int i) {
    std::size_t v = 0;
    for (const std::span<double>& a : items[static_cast<std::size_t>(i)]) v += a.size();
    return static_cast<int>(v);
  };
  // The items asked of each rank, rank after rank.
  std::vector<std::vector<int>> asked(static_cast<std::size_t>(p));
  for (const int i : needed) {
    if (i < 0 || i >= static_cast<int>(items.size()) || owner[static_cast<std::size_t>(i)] == ranks.rank())
      throw std::invalid_argument("bring_items: item " + std::to_string(i) + " is not another rank's");
    asked[static_cast<std::size_t>(owner[static_cast<std::size_t>(i)])].push_back(i);
  }
  std::vector<int> ask, ask_counts(static_cast<std::size_t>(p)), value_in_counts(static_cast<std::size_t>(p), 0);
  for (int r = 0; r < p; ++r) {
    ask.insert(ask.end(), asked[static_cast<std::size_t>(r)].begin(), asked[static_cast<std::size_t>(r)].end());
    ask_counts[static_cast<std::size_t>(r)] = static_cast<int>(asked[static_cast<std::size_t>(r)].size());
    for (const int i : asked[static_cast<std::size_t>(r)]) value_in_counts[static_cast<std::size_t>(r)] += values_of(i);
  }
  const std::vector<int> wanted_counts = ranks.exchange_counts(ask_counts);
  std::vector<int> wanted(static_cast<std::size_t>(std::accumulate(wanted_counts.begin(), wanted_counts.end(), 0)));
  ranks.exchange(ask, ask_counts, wanted, wanted_counts);
  // This rank's items that the others asked for, their values rank after rank.
  std::vector<double> out;
  std::vector<int> value_out_counts(static_cast<std::size_t>(p), 0);
  auto next = wanted.cbegin();
  for (int r = 0; r < p; ++r) {
    for (int k = 0; k < wanted_counts[static_cast<std::size_t>(r)]; ++k, ++next) {
      const int i = *next;
      if (i < 0 || i >= static_cast<int>(items.size()) || owner[static_cast<std::size_t>(i)] != ranks.rank())
        throw std::logic_error("bring_items: asked for item " + std::to_string(i) + ", not this rank's");
      for (const std::span<double>& a : items[static_cast<std::size_t>(i)]) out.insert(out.end(), a.begin(), a.end());
      value_out_counts[static_cast<std::size_t>(r)] += values_of(i);
    }
  }
  std::vector<double> in(static_cast<std::size_t>(
      std::accumulate(value_in_counts.begin(), value_in_counts.end(), 0)));
  ranks.exchange(out, value_out_counts, in, value_in_counts);
  auto from = in.cbegin();
  for (const int i : ask)
    for (const std::span<double>& a : items[static_cast<std::size_t>(i)]) {
      std::copy(from, from + static_cast<long>(a.size()), a.begin());
      from += static_cast<long>(a.size());
    }
  return static_cast<int>(ask.size());
}

}  // namespace rbcflow
