#pragma once
// A node of the regular rule inside a target's patch, with its partition-of-unity weight eta:
// the share of that node's regular term which the patch integral I_1 replaces (section 5.4,
// eq. 31-33). Built by the singular corrections (quadrature/singular_quadrature.h), read by the
// real-space Ewald sums that weight such pairs by 1 - eta (spme/real_space_sum.h PairShares).
// 6 bytes a node, as many as a step holds for the double layer's patches (1.4 MB a cell at
// N = 16): the node's index among its cell's nodes, below kMaxNodes (cells.order <= 128 has
// 33,024), and eta in single precision. Every correction folds or removes this same rounded
// share, as the real-space sums read it, so folding a node stays exact; the rounding (~6e-8)
// is far below the patch rule's error.
#include <cstdint>
#include <cstring>

namespace rbcflow {

class PatchNode {
 public:
  static constexpr int kMaxNodes = 1 << 16;
  PatchNode() = default;
  // node in [0, kMaxNodes): the caller checks (the cell's grid).
  PatchNode(int node, float eta) : node_(static_cast<std::uint16_t>(node)) { std::memcpy(eta_, &eta, sizeof eta); }
  int node() const { return node_; }
  float eta() const {
    float e;
    std::memcpy(&e, eta_, sizeof e);
    return e;
  }

 private:
  std::uint16_t node_ = 0;
  std::uint16_t eta_[2] = {0, 0};  // the float's bytes, 2-byte aligned: no padding
};
static_assert(sizeof(PatchNode) == 6);

}  // namespace rbcflow
