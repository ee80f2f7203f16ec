#pragma once
// Which cells a rank owns: a contiguous block of the cell indices, the blocks of the ranks in
// rank order and differing in size by at most one. The owner of a cell builds and applies its
// quadrature corrections and sums its nodes as sources into the Ewald sums (cell_layers.h);
// every rank holds every cell's shape (communicator.h).
#include "libsolver/parallel/communicator.h"

namespace rbcflow {

struct OwnedRange {
  int begin = 0, end = 0;  // [begin, end)
  int size() const { return end - begin; }
  bool empty() const { return end == begin; }
  bool contains(int i) const { return begin <= i && i < end; }
};

// The block of n items of rank r of p: the first n % p ranks take one more.
inline OwnedRange owned_block(int n, int r, int p) {
  const int base = n / p, extra = n % p;
  const int begin = r * base + (r < extra ? r : extra);
  return {begin, begin + base + (r < extra ? 1 : 0)};
}
inline OwnedRange owned_block(int n, const Communicator& ranks) { return owned_block(n, ranks.rank(), ranks.size()); }

}  // namespace rbcflow
