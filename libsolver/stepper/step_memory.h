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
// every block of 256 kB or more is mapped on its own and unmapped when freed, so the resident
// memory is what is live, at the price of faulting each step's workspaces in again.
// The scenario layer chooses one of them for each run (scenario/memory_budget.h); neither
// changes a result. Each returns false where the C library does not take the settings (then
// nothing changed).
namespace rbcflow {

bool reuse_freed_memory();
bool return_freed_memory();

}  // namespace rbcflow
