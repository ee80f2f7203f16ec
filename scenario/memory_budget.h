#pragma once
// What a run will hold at the peak of a time step, estimated from the prepared scenario before
// anything is built, by part, and the budget it must fit in ([solver] memory_gib, or the
// machine's physical memory). The model is the bytes of each structure a step keeps (the
// breakdown `bench_step` prints, libsolver's MemoryReport), per unit that sets its size:
//   cells' geometry      2 fields x (2N+1) x 4N Hermite nodes x 12 doubles + 7 doubles per node
//   singular (self)      double layer: P Q float kernels of 6 + 2.3 P^2 bytes of node entries
//   nearly singular      double layer: 2 H P near targets per cell (at least 0.05 P), each
//                        Q (12 + 24) bytes (stencil, kernel) + 2.25 kB of node entries
//                        (node entries: the patch nodes within the real-space cutoff but
//                        beyond half the box, none where the box is twice the cutoff across)
//   cells' Ewald sum     double layer: pairs = nodes x (4 pi/3) r_c^3 x nodes / lumen volume
//                        (the cells fill the lumen, not the box), 2.2 bytes each in the coded
//                        list (bench_spme BM_NeighborList) and
//                        16 kept; 4.1 P bytes of pair shares (6-byte folded patch nodes) and
//                        250 bytes of stencils per node;
//                        one product's work arrays, 48 bytes per grid point (two arrays of 3
//                        grids, transformed in place; 32 with lean transforms, below)
//   wall                 54.9 kB per wall node (operator, near field, preconditioner) and the
//                        recycled space, 48 bytes per node and direction (WallSolveOptions::recycle)
//   cells <-> wall       17.0 kB per wall node and 1.7 kB per cell node (no kept pair
//                        coefficients: each of these operators is applied once a step)
//   peak                 1.3 x the sum (what a step builds and frees) + 60 MB for the program;
//                        1.1 x when the run returns what its steps free (below)
// with P = 2N^2 nodes per cell, Q patch points per target, H the tube hematocrit. The single
// layer holds nothing past its build (cell_layers.h). Calibrated at 303b38c on bench_step's
// tube27 (N = 16, lambda = 5, Ewald 1e-6: predicted and measured peak in docs/performance.md),
// the coupling on tube27 and wide125 together (its two constants; wide512 then within 4%);
// the parts of other cases scale as above.
//
// On P ranks (mpirun) each rank holds its own cells' share of what is split and all of what is
// repeated (docs/scaling.md). The split fractions, measured part by part on bench_step tube8
// (2 ranks against 1 process, 79b58a5 and, for the wall, the commit that freed its near field):
// the cells' geometry, corrections and Ewald pairs, and the cell-wall coupling but for the
// wall's stencils at the cells (0.9), are split; of the Ewald work arrays 0.15 with FFTW's MPI
// library (the slabs), else none; the wall's assembled real-space rows, their spreading rows and
// grid, the preconditioner's blocks and the recycled space are split (of the wall 0.91 without
// the slabs: the smooth part's grid is then whole on every rank). The wall's 54.9 kB a node are
// the 67.1 calibrated with the LU of the whole local near field (14.7 kB a node of tube27's
// wall, repeated on every rank), less that LU, plus the preconditioner's blocks of 500 nodes
// (2.5 kB a node; bench_wall WallBlocks/27 at e5920a6).
// The ranks on one machine share its memory: each gets the budget divided by their number.
#include <string>
#include <vector>

#include "io/case.h"

namespace rbcflow {

struct Scenario;

// The ranks a run is split over: `ranks` in all, at most `per_machine` of them on one machine.
struct RankLayout {
  int ranks = 1;
  int per_machine = 1;
};

struct MemoryEstimate {
  // The peak as a factor of what a step holds: what it builds and frees besides, with the
  // heaps keeping freed memory (tube27 1.27, tube64 1.29) or returning it (bench_step wide1000:
  // 1.08 at 4c3a3e2, the peak in a cell product with its work arrays).
  static constexpr double kPeakFactorKept = 1.3;
  static constexpr double kPeakFactorReturned = 1.1;
  struct Part {
    std::string name;
    double bytes = 0;  // on one process
    double split = 0;  // the fraction of `bytes` divided over the ranks
  };
  std::vector<Part> parts;
  double kept_coefficients = 0;  // of the cells' Ewald part (split): what not keeping them saves
  double lean_transforms = 0;    // of the cells' Ewald part: what lean transforms save
  int ranks = 1;
  double peak_factor = kPeakFactorKept;  // kPeakFactorReturned where freed memory is returned
  double on_each_rank(const Part& p) const { return p.bytes * (1.0 - p.split + p.split / ranks); }
  double parts_total() const;  // of each rank
  double total() const;        // the peak of each rank: peak_factor x its parts + the program
};

MemoryEstimate estimate_memory(const Scenario& s, int ranks = 1);

// Bytes: [solver] memory_gib, or the machine's physical memory when it is not set (infinite
// where the system does not say); for each rank its share of its machine.
double memory_budget(const Case& c, int ranks_per_machine = 1);

// Fits the scenario's estimate (s.memory) for `layout` into the budget (s.memory_budget, per
// rank): keeps the Ewald pair coefficients when everything fits with them, drops them
// (products recompute them: slower, no less accurate) when only then it fits, and otherwise
// throws CaseError naming solver.memory_gib with the estimate and what to change. `layout`:
// the run's ranks and those on this rank's machine. A run whose estimate is above 3/4 of its
// budget has its freed memory returned to the system instead of kept for the next steps
// (s.reuses_freed_memory; libsolver/stepper/step_memory.h), its estimate's peak factor 1.1
// instead of 1.3, and the double layer's transforms lean (s.options.domain.lean_transforms: 32
// bytes a grid point instead of 48, the estimate's part lowered by that). In a run on several ranks
// (s.options.domain.ranks) every rank takes the decision of the smallest of the ranks'
// budgets, so that all hold the same operators.
void apply_memory_budget(Scenario& s, RankLayout layout);

// Once the Ewald sums are chosen again without the kept coefficients (apply_memory_budget
// dropped them; the double layer's choice then changes): the estimate of what the run will
// hold, in the memory mode already decided, so that `rbcflow check` prints the run's figure;
// refused as above if that choice does not fit.
void estimate_memory_without_kept_pairs(Scenario& s, RankLayout layout);

}  // namespace rbcflow
