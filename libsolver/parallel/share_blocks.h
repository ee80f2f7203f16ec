#pragma once
// Per-item data computed by each item's owner in blocks (owned_block: a rank's block of the
// items, in rank order), made whole on every rank: the cells' membrane states after each rank
// computed its own, their shapes after each rank moved its own (cell_stepper.h, collision.h).
// The values are packed item after item, the blocks gathered (MPI_Allgatherv) and unpacked:
// every rank then holds the owners' bits.
#include <span>
#include <vector>

#include "libsolver/parallel/communicator.h"

namespace rbcflow {

// items[i]: the arrays of item i (their sizes the same on every rank), filled on its owner;
// on return filled on every rank. One rank: nothing to do.
void share_blocks(const Communicator& ranks, const std::vector<std::vector<std::span<double>>>& items);

}  // namespace rbcflow
