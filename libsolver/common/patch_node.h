#pragma once
// A node of the regular rule inside a target's patch, with its partition-of-unity weight eta:
// the share of that node's regular term which the patch integral I_1 replaces (section 5.4,
// eq. 31-33). Built by the singular corrections (quadrature/singular_quadrature.h), read by the
// real-space Ewald sums that weight such pairs by 1 - eta (spme/real_space_sum.h PairShares).
// eta is kept in single precision (8 bytes a node): every correction folds or removes this same
// rounded share, as the real-space sums read it, so folding a node stays exact; the rounding
// (~6e-8) is far below the patch rule's error.
namespace rbcflow {

struct PatchNode {
  int node;
  float eta;
};

}  // namespace rbcflow
