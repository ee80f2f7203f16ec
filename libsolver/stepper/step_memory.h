#pragma once
// Every time step allocates its geometry-dependent workspaces afresh (singular-correction
// tables, neighbour lists, kept Ewald pair coefficients: hundreds of MB for tens of cells) and
// frees them at its end. glibc serves blocks over 32 MB by mmap and returns them to the system
// when freed, so the next step faults the same amount of memory in again, page by page; on a
// virtual machine that is a measurable part of a step (bench_step tube8: 8%).
// reuse_freed_memory() asks malloc to serve blocks from its heaps and never to trim them:
// a run's later steps then reuse the first steps' pages. Call it once, at program start, in
// programs that run time steps (rbcflow, bench_step); it changes no result.
// Returns false where the C library does not take the settings (then nothing changed).
namespace rbcflow {

bool reuse_freed_memory();

}  // namespace rbcflow
