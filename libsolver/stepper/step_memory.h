#pragma once
// Every time step allocates its geometry-dependent workspaces afresh (singular-correction
// tables, neighbour lists, kept Ewald pair coefficients: hundreds of MB for tens of cells) and
// frees them at its end. glibc serves blocks over 32 MB by mmap and returns them to the system
// when freed, so the next step faults the same amount of memory in again, page by page; on a
// virtual machine that is a measurable part of a step (bench_step tube8: 8%).
// reuse_freed_memory() asks malloc to serve blocks from its heaps and never to trim them:
// a run's later steps then reuse the first steps' pages. The price is the peak: the heaps keep
// what a step's build freed, and the next structures do not always fit in those holes
// (wide125: peak 1.3 x what a step holds).
// return_freed_memory() is the opposite, for a run whose estimate is close to its budget:
// every block of 8 MB or more is mapped on its own and unmapped when freed; smaller blocks (a
// cell's correction tables and the workspaces of its build) come from the heaps, where the next
// cell's build reuses what the last one freed, and release_heap_memory() gives what the heaps
// hold free back to the system. The stepper calls it where a step's builds are done (before
// the first and after the last of its operators is built), so that the resident memory at the
// products, where the step peaks, is what is live; each step faults its workspaces in again.
// (With every block of 256 kB or more mapped, the 1,000 cells took 16 million page faults in a
// step against 7 million, docs/performance.md.)
// The scenario layer chooses one of them for each run (scenario/memory_budget.h); neither
// changes a result. Each returns false where the C library does not take the settings (then
// nothing changed).
namespace rbcflow {

bool reuse_freed_memory();
bool return_freed_memory();
// After return_freed_memory(): the heaps' free memory back to the system (malloc_trim); else
// nothing.
void release_heap_memory();

}  // namespace rbcflow
