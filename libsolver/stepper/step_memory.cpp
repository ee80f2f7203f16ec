#include "step_memory.h"

#include <malloc.h>

#include <atomic>

namespace rbcflow {
namespace {
std::atomic<bool> returning{false};  // return_freed_memory() in force
}

bool reuse_freed_memory() {
  returning = false;
  // No block by mmap (blocks of any size come from the heap and stay there when freed; a
  // thread's arena still maps a block larger than its 64 MB heap), and no trimming (-1: freed
  // memory at the top of a heap is kept).
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, -1) == 1;
}

bool return_freed_memory() {
  // Mapping allowed again (glibc's default count), a fixed threshold (the default one rises to
  // the size of each mapped block freed, up to 32 MB), and the heap's top trimmed past 1 MB. At
  // 8 MB a thousand cells' per-node vectors (12 MB) are mapped, and most blocks of one cell's
  // build are not.
  constexpr int kMapped = 8 << 20, kTrim = 1 << 20, kMaxMaps = 65536;
  returning = mallopt(M_MMAP_MAX, kMaxMaps) == 1 && mallopt(M_MMAP_THRESHOLD, kMapped) == 1 &&
              mallopt(M_TRIM_THRESHOLD, kTrim) == 1;
  return returning;
}

void release_heap_memory() {
  if (returning) malloc_trim(0);
}

}  // namespace rbcflow
