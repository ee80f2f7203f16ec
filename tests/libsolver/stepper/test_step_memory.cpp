#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "libsolver/stepper/step_memory.h"

using namespace rbcflow;

// The tests measure glibc's heap under a setting (`apply`, which returns false where the C
// library does not take it): skipped under AddressSanitizer, whose allocator quarantines freed
// blocks instead, and where the setting is not taken.
#if defined(__SANITIZE_ADDRESS__)
#define SKIP_UNLESS_GLIBC_HEAP(apply) \
  GTEST_SKIP() << "AddressSanitizer's allocator quarantines freed blocks: glibc's heap is not in use"
#else
#define SKIP_UNLESS_GLIBC_HEAP(apply) \
  do {                                \
    if (!(apply)) GTEST_SKIP() << "this C library does not take the malloc settings"; \
  } while (0)
#endif

namespace {

long minor_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

// The resident memory of the process, kB (VmRSS).
long resident_kb() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::atol(line.c_str() + 6);
  return -1;
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
  SKIP_UNLESS_GLIBC_HEAP(reuse_freed_memory());
  const std::size_t bytes = std::size_t{64} << 20;
  const long pages = static_cast<long>(bytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  const long first = faults_to_fill(bytes), second = faults_to_fill(bytes);
  std::printf("64 MB block (%ld pages): %ld page faults to fill it first, %ld the second time\n", pages, first, second);
  EXPECT_GT(first, pages / 2);   // the first block is new memory
  EXPECT_LT(second, pages / 100);  // the second reuses it
}

// The opposite setting, for runs close to their memory budget: a block of 16 MB (above the
// 8 MB threshold) written, freed, and written again three times. Each time it is mapped afresh
// (faulting its pages in) and unmapped when freed, never left in a heap. With glibc's default
// threshold, which rises to the size of a mapped block freed, the third comes from the heap
// without a fault (measured: 4,096, 4,095, 0 faults). A first block, before the three, may come
// from what the heap held.
TEST(StepMemory, LargeFreedBlocksAreReturnedWhenMemoryIsShort) {
  SKIP_UNLESS_GLIBC_HEAP(return_freed_memory());
  const std::size_t bytes = std::size_t{16} << 20;
  const long pages = static_cast<long>(bytes / static_cast<std::size_t>(sysconf(_SC_PAGESIZE)));
  faults_to_fill(bytes);
  for (int k = 0; k < 3; ++k) {
    const long faults = faults_to_fill(bytes);
    std::printf("16 MB block (%ld pages), fill %d: %ld page faults\n", pages, k + 1, faults);
    EXPECT_GT(faults, pages / 2);
  }
}

// Smaller blocks freed stay in the heap, where the next ones reuse them without page faults
// (a cell's build after the last one's), until release_heap_memory() gives their pages back:
// 64 blocks of 1 MB, each followed by a small block that stays (so that the freed ones cannot
// merge into the heap's top, which free() trims by itself), written and freed.
TEST(StepMemory, SmallFreedBlocksWaitForTheRelease) {
  SKIP_UNLESS_GLIBC_HEAP(return_freed_memory());
  constexpr std::size_t kBlock = std::size_t{1} << 20;
  constexpr int kBlocks = 64;
  release_heap_memory();
  const long before = resident_kb();
  std::vector<char*> blocks, pins;
  for (int k = 0; k < kBlocks; ++k) {
    blocks.push_back(static_cast<char*>(std::malloc(kBlock)));
    pins.push_back(static_cast<char*>(std::malloc(64)));
    ASSERT_TRUE(blocks.back() && pins.back());
    std::memset(blocks.back(), 1, kBlock);
  }
  const long written = resident_kb() - before;
  for (char* b : blocks) std::free(b);
  const long freed = resident_kb() - before;
  const long refill_faults = faults_to_fill(kBlock);
  release_heap_memory();
  const long released = resident_kb() - before;
  for (char* p : pins) std::free(p);
  std::printf("64 x 1 MB: resident +%ld kB written, +%ld kB freed, +%ld kB released; %ld faults to fill a freed block\n",
              written, freed, released, refill_faults);
  EXPECT_GT(written, 60 * 1024);
  EXPECT_GT(freed, 60 * 1024);     // kept in the heap
  EXPECT_LT(refill_faults, 256 / 10);  // and reused: a fresh 1 MB block takes 256 faults
  EXPECT_LT(released, 8 * 1024);   // given back
}
