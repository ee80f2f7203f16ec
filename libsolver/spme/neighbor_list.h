#pragma once
// Source-target pairs closer than a cutoff in a periodic box, found once with cell lists and
// kept for every product with the same positions (section 5.3). Sources and targets may be
// different point sets (cells, wall nodes, quadrature points).
//
// Images: a pair is (source s, lattice vector n) with r = x_s + n L - x_t, |r| < cutoff; every
// image inside the cutoff is listed, so cutoffs beyond half a box side are handled exactly.
// Coincident points: pairs with |r| <= coincidence_distance() (1e-12 V^(1/3)), the r = 0 of a
// source that is also a target, are left out: the real-space kernel is singular there and the
// singular quadrature accounts for it (its regular part is ewald_real_stokeslet_self).
//
// The pairs are stored compactly, about 2 bytes each instead of 6 (a source index and an image
// id): a target's pairs, in the order of its search (cell by cell, sources ascending), as the
// 16-bit difference of each source index from the one before, with an escape word followed by
// the full index and the image id where the image changes or the step does not fit (a few
// times a target, where the search moves to another row or plane of cells).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "libsolver/common/periodic_box.h"

namespace rbcflow {

class NeighborList {
 public:
  // Throws std::invalid_argument for a non-positive cutoff or one beyond 16 box lengths.
  NeighborList(const PeriodicBox& box, double cutoff, const PointField& sources,
               const PointField& targets);

  const PeriodicBox& box() const { return box_; }
  double cutoff() const { return cutoff_; }
  double coincidence_distance() const { return coincidence_; }
  int n_sources() const { return static_cast<int>(order_.size()); }
  int n_targets() const { return static_cast<int>(targets_.size() / 3); }
  std::int64_t n_pairs() const { return offsets_.back(); }
  std::size_t memory_bytes() const;

  // Sources are stored sorted by cell: sorted index i is the caller's source order()[i].
  const std::vector<int>& order() const { return order_; }
  // Targets likewise; visiting them in target_order() keeps the memory accesses local.
  const std::vector<int>& target_order() const { return target_order_; }

  // Calls f(sorted source index, r) for every pair of the caller's target t, r = x_s + n L - x_t.
  template <class F>
  void for_each_neighbor(int t, F&& f) const {
    for_each_pair(t, [&](std::int64_t, int s, const Eigen::Vector3d& r) { f(s, r); });
  }
  // The same with the pair's index in [0, n_pairs()) first (for data kept per pair).
  template <class F>
  void for_each_pair(int t, F&& f) const {
    const std::size_t k = static_cast<std::size_t>(rank_[t]);
    const double* xt = &targets_[3 * k];
    const std::uint16_t* code = codes_.data() + code_offsets_[k];
    int s = 0;
    const double* shift = &image_shifts_[3 * static_cast<std::size_t>(home_image_)];
    for (std::int64_t i = offsets_[k]; i < offsets_[k + 1]; ++i) {
      const auto step = static_cast<std::int16_t>(*code++);
      if (step == kEscape) [[unlikely]] {
        s = static_cast<int>(code[0] | (static_cast<std::uint32_t>(code[1]) << 16));
        shift = &image_shifts_[3 * static_cast<std::size_t>(code[2])];
        code += 3;
      } else {
        s += step;
      }
      const double* xs = &sources_[3 * static_cast<std::size_t>(s)];
      f(i, s, Eigen::Vector3d(xs[0] + shift[0] - xt[0], xs[1] + shift[1] - xt[1],
                              xs[2] + shift[2] - xt[2]));
    }
  }

 private:
  PeriodicBox box_;
  double cutoff_, coincidence_;
  std::vector<int> order_;             // sorted -> caller's source index
  std::vector<double> sources_;        // wrapped source positions, sorted, xyz interleaved
  std::vector<int> target_order_;      // sorted -> caller's target index
  std::vector<int> rank_;              // caller's target index -> sorted
  std::vector<double> targets_;        // wrapped target positions, sorted, xyz interleaved
  std::vector<double> image_shifts_;   // n L for each image id, xyz interleaved
  std::vector<std::int64_t> offsets_;  // pairs of sorted target k: [offsets_[k], offsets_[k + 1])
  // The pairs of sorted target k coded from codes_[code_offsets_[k]] on, each a step of the
  // source index from the pair before (from source 0 in the home image, n = 0, for the first)
  // or kEscape, the source's low and high 16 bits and the image id.
  static constexpr std::int16_t kEscape = INT16_MIN;
  int home_image_ = 0;
  std::vector<std::int64_t> code_offsets_;
  std::vector<std::uint16_t> codes_;
};

}  // namespace rbcflow
