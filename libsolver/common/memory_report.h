#pragma once
// What the solver's data structures hold, by name, for the memory breakdown of a time step
// (FlowSolution::memory, bench/bench_step.cpp, docs/performance.md). Each structure adds the
// bytes of its own arrays (capacity, not size); memory shared between two structures is added
// by one of them. Measuring changes no result.
#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <cstddef>
#include <string>
#include <vector>

namespace rbcflow {

class MemoryReport {
 public:
  struct Item {
    std::string name;
    std::size_t bytes = 0;
  };
  // Adds to the item of that name (created in the order of first use).
  void add(const std::string& name, std::size_t bytes) {
    for (Item& i : items_)
      if (i.name == name) {
        i.bytes += bytes;
        return;
      }
    items_.push_back({name, bytes});
  }
  // Raises the item of that name to `bytes` if it holds less: for memory that is allocated for
  // one operation at a time and shared, through the allocator, by operations that follow each other.
  void add_max(const std::string& name, std::size_t bytes) {
    for (Item& i : items_)
      if (i.name == name) {
        if (i.bytes < bytes) i.bytes = bytes;
        return;
      }
    items_.push_back({name, bytes});
  }
  const std::vector<Item>& items() const { return items_; }
  std::size_t total() const {
    std::size_t t = 0;
    for (const Item& i : items_) t += i.bytes;
    return t;
  }

 private:
  std::vector<Item> items_;
};

template <class Container>
std::size_t heap_bytes(const Container& c) {
  return c.capacity() * sizeof(typename Container::value_type);
}
template <class Derived>
std::size_t matrix_bytes(const Eigen::DenseBase<Derived>& m) {
  return static_cast<std::size_t>(m.size()) * sizeof(typename Derived::Scalar);
}

template <class Scalar, int Options, class Index>
std::size_t matrix_bytes(const Eigen::SparseMatrix<Scalar, Options, Index>& m) {
  return static_cast<std::size_t>(m.nonZeros()) * (sizeof(Scalar) + sizeof(Index)) +
         static_cast<std::size_t>(m.outerSize() + 1) * sizeof(Index);
}

}  // namespace rbcflow
