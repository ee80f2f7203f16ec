#include "held_shapes.h"

#include <cmath>
#include <span>
#include <stdexcept>
#include <string>

#include "libsolver/parallel/share_blocks.h"

namespace rbcflow {

void release_shape(SHCoeffs& x) { x.values().resize(0, x.values().cols()); }

SHCoeffs shape_not_held(int order) {
  SHCoeffs x(order, 3);
  release_shape(x);
  return x;
}

void allocate_shape(SHCoeffs& x) {
  if (shape_held(x)) return;
  const int columns = x.values().cols() > 0 ? static_cast<int>(x.values().cols()) : 3;
  x = SHCoeffs(x.order(), columns);
  x.values().setConstant(std::nan(""));
}

namespace {

std::span<double> values_of(SHCoeffs& x) {
  return {x.values().data(), static_cast<std::size_t>(x.values().size())};
}

void check_sizes(const std::vector<SHCoeffs*>& shapes, const CellOwners& held_by) {
  if (shapes.size() != held_by.order.size())
    throw std::invalid_argument("held shapes: " + std::to_string(shapes.size()) + " shapes for " +
                                std::to_string(held_by.order.size()) + " cells");
}

}  // namespace

int bring_shapes(const std::vector<SHCoeffs*>& shapes, const CellOwners& held_by, const std::vector<int>& cells,
                 const Communicator& ranks) {
  check_sizes(shapes, held_by);
  if (ranks.size() == 1) return 0;
  const int n = static_cast<int>(shapes.size());
  std::vector<int> owner(static_cast<std::size_t>(n));
  for (int r = 0; r < ranks.size(); ++r)
    for (int k = held_by.first[r]; k < held_by.first[r + 1]; ++k) owner[static_cast<std::size_t>(held_by.order[k])] = r;
  std::vector<std::vector<std::span<double>>> items(static_cast<std::size_t>(n));
  for (int k = held_by.first[ranks.rank()]; k < held_by.first[ranks.rank() + 1]; ++k) {
    SHCoeffs& own = *shapes[static_cast<std::size_t>(held_by.order[k])];
    if (!shape_held(own)) throw std::logic_error("bring_shapes: a cell of this rank's without its shape");
    items[static_cast<std::size_t>(held_by.order[k])] = {values_of(own)};
  }
  std::vector<int> needed;
  for (const int c : cells) {
    if (c < 0 || c >= n) throw std::invalid_argument("bring_shapes: no cell " + std::to_string(c));
    if (owner[static_cast<std::size_t>(c)] == ranks.rank()) continue;
    SHCoeffs& x = *shapes[static_cast<std::size_t>(c)];
    allocate_shape(x);
    items[static_cast<std::size_t>(c)] = {values_of(x)};
    needed.push_back(c);
  }
  return bring_items(ranks, owner, needed, items);
}

void share_shapes(const std::vector<SHCoeffs*>& shapes, const CellOwners& held_by, const Communicator& ranks) {
  check_sizes(shapes, held_by);
  if (ranks.size() == 1) return;
  const int r = ranks.rank();
  std::vector<std::vector<std::span<double>>> items;
  for (int k = 0; k < static_cast<int>(held_by.order.size()); ++k) {
    SHCoeffs& x = *shapes[static_cast<std::size_t>(held_by.order[k])];
    if (k >= held_by.first[r] && k < held_by.first[r + 1] && !shape_held(x))
      throw std::logic_error("share_shapes: a cell of this rank's without its shape");
    allocate_shape(x);
    items.push_back({values_of(x)});
  }
  share_blocks(ranks, items);
}

}  // namespace rbcflow
