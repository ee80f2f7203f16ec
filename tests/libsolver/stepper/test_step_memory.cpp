#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>

#include "libsolver/stepper/step_memory.h"

using namespace rbcflow;

namespace {

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// Page faults taken while writing a fresh block of `bytes` (the block is freed again).
long faults_to_fill(std::size_t bytes) {
  char* p = static_cast<char*>(std::malloc(bytes));
  if (!p) return -1;
  const long before = minor_faults();
  std::memset(p, 1, bytes);
  const long faults = minor_faults() - before;
  EXPECT_EQ(p[bytes - 1], 1);
  std::free(p);
  return faults;
}

}  // namespace

// What a time step does with its workspaces: a block of 64 MB (above glibc's largest mmap
// threshold, 32 MB) allocated, written, freed, and allocated again. Without the setting the
// second block is mapped afresh and faults every page in again; with it the pages are reused.
TEST(StepMemory, FreedBlocksAreReusedWithoutPageFaults) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator quarantines freed blocks: glibc's heap is not in use";
#endif
  if (!reuse_freed_memory()) GTEST_SKIP() << "this C library does not take the malloc settings";
  const std::size_t bytes = std::size_t{64} << 20;
  const long pages = static_cast<long>(bytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  const long first = faults_to_fill(bytes), second = faults_to_fill(bytes);
  std::printf("64 MB block (%ld pages): %ld page faults to fill it first, %ld the second time\n", pages, first, second);
  EXPECT_GT(first, pages / 2);   // the first block is new memory
  EXPECT_LT(second, pages / 100);  // the second reuses it
}

// The opposite setting, for runs close to their memory budget: a block of 1 MB (below glibc's
// default threshold once it has risen) written, freed, and written again three times. Each
// time it is mapped afresh (faulting its pages in) and unmapped when freed, never left in a
// heap. With glibc's default the third block is served from the heap without a fault (measured:
// 257, 255, 0 faults). A first block, before the three, may come from what the heap held.
TEST(StepMemory, FreedBlocksAreReturnedWhenMemoryIsShort) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator quarantines freed blocks: glibc's heap is not in use";
#endif
  if (!return_freed_memory()) GTEST_SKIP() << "this C library does not take the malloc settings";
  const std::size_t bytes = std::size_t{1} << 20;
  const long pages = static_cast<long>(bytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  faults_to_fill(bytes);
  for (int k = 0; k < 3; ++k) {
    const long faults = faults_to_fill(bytes);
    std::printf("1 MB block (%ld pages), fill %d: %ld page faults\n", pages, k + 1, faults);
    EXPECT_GT(faults, pages / 2);
  }
}
