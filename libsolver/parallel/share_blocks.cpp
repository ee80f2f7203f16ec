#include "share_blocks.h"

#include <algorithm>

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

}  // namespace rbcflow
