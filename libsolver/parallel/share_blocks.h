#pragma once
// Per-item data computed by each item's owner in blocks (owned_block: a rank's block of the
// items, in rank order), made whole on every rank: the cells' membrane states after each rank
// computed its own, their shapes after each rank moved its own (cell_stepper.h, collision.h).
// The values are packed item after item, the blocks gathered (MPI_Allgatherv) and unpacked:
// every rank then holds the owners' bits. bring_items brings a rank only the items it reads:
// the shapes of the cells near its own in the collision removal.
#include <span>
#include <vector>

#include "libsolver/parallel/communicator.h"

namespace rbcflow {

// items[i]: the arrays of item i (their sizes the same on every rank), filled on its owner;
// on return filled on every rank. One rank: nothing to do.
void share_blocks(const Communicator& ranks, const std::vector<std::vector<std::span<double>>>& items);

// The items this rank reads of those other ranks fill (`needed`: item numbers, none of them
// this rank's; owner[i] the rank that fills item i), brought from their owners: only those
// travel, not every item to every rank (two exchanges: the items asked for, then their values).
// The arrays' sizes are the same on every rank. Returns how many items were brought here.
// Collective. One rank: nothing to do.
int bring_items(const Communicator& ranks, const std::vector<int>& owner, const std::vector<int>& needed,
                const std::vector<std::vector<std::span<double>>>& items);

}  // namespace rbcflow
