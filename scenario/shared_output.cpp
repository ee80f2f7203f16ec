#include "scenario/shared_output.h"

#include "libsolver/parallel/ownership.h"

namespace rbcflow {

std::pair<long long, long long> rows_to_write(long long rows, long cells, const Communicator& ranks) {
  if (cells > 0 && rows % cells == 0) {
    const OwnedRange owned = owned_block(static_cast<int>(cells), ranks);
    const long long per_cell = rows / cells;
    return {owned.begin * per_cell, owned.end * per_cell};
  }
  const OwnedRange block = owned_block(static_cast<int>(rows), ranks);
  return {block.begin, block.end};
}

std::optional<XdmfWriter::Ranks> frame_writers(const Communicator& ranks, long cells) {
  if (ranks.size() == 1 || !XdmfWriter::shared_by_ranks()) return std::nullopt;
  return XdmfWriter::Ranks{ranks.mpi_handle(), ranks.rank(),
                           [ranks, cells](const std::string&, long long rows) { return rows_to_write(rows, cells, ranks); },
                           [ranks](bool mine) { return ranks.min(mine ? 1.0 : 0.0) == 1.0; }};
}

}  // namespace rbcflow
