#include "step_memory.h"

#include <malloc.h>

namespace rbcflow {

bool reuse_freed_memory() {
  // No block by mmap (blocks of any size come from the heap and stay there when freed; a
  // thread's arena still maps a block larger than its 64 MB heap), and no trimming (-1: freed
  // memory at the top of a heap is kept).
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, -1) == 1;
}

}  // namespace rbcflow
