#pragma once
// Which part of the output files each rank of a run writes when the ranks write them together
// (parallel HDF5: the checkpoints, io/checkpoint.h, and the frames of rbcflow.h5,
// io/xdmf_writer.h): each writes the rows of its block of the cells (owned_block,
// libsolver/parallel/ownership.h; a frame's cells are brought to it, CellStepper::
// cells_for_output, a checkpoint's state gathered) and a block of the rows of everything
// else, so that the ranks' rows cover each array once.
#include <optional>
#include <utility>

#include "io/xdmf_writer.h"
#include "libsolver/parallel/communicator.h"

namespace rbcflow {

// The rows [begin, end) of an array of `rows` rows that this rank writes: an array with a row
// per cell, per cell node, point or triangle (rows a multiple of `cells`) by the cells' owners,
// any other in contiguous blocks over the ranks (one row: rank 0's).
std::pair<long long, long long> rows_to_write(long long rows, long cells, const Communicator& ranks);

// The ranks' shares of the frames of rbcflow.h5, when there are several ranks and the build can
// write one file from all of them; else none (rank 0 writes the frames alone).
std::optional<XdmfWriter::Ranks> frame_writers(const Communicator& ranks, long cells);

}  // namespace rbcflow
