#include "scenario/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "libsolver/parallel/slab_fft.h"
#include "libsolver/quadrature/singular_quadrature.h"
#include "scenario/scenario.h"

namespace rbcflow {

namespace {

// Up to this fraction of the budget a run's heaps keep what its steps free, for the next steps
// (libsolver/stepper/step_memory.h); above it they return it. bench_step wide512 (0.69 of a
// 23.5 GiB machine) ran with its heaps kept; wide1000 (0.96) was killed for memory in its first
// step's build with them kept, and runs with them returned (peak 0.83 of the budget).
constexpr double kReuseFreedMemory = 0.75;
constexpr double kProgramBytes = 60e6;
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

// The fractions of the parts that the ranks split (memory_budget.h).
constexpr double kSplitEwaldWorkArrays = 0.15;  // with the slabs; none without
constexpr double kSplitWall = 1.0;               // with the slabs
constexpr double kSplitWallWithoutSlabs = 0.91;
constexpr double kSplitCoupling = 0.9;

const EwaldSum* find_sum(const Scenario& s, const std::string& what) {
  for (const EwaldSum& e : s.ewald)
    if (e.what == what) return &e;
  return nullptr;
}

std::string gib(double bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.2f GiB", bytes / kGiB);
  return b;
}

}  // namespace

double MemoryEstimate::parts_total() const {
  double sum = 0;
  for (const Part& p : parts) sum += on_each_rank(p);
  return sum;
}

double MemoryEstimate::total() const { return peak_factor * parts_total() + kProgramBytes; }

MemoryEstimate estimate_memory(const Scenario& s, int ranks) {
  MemoryEstimate m;
  m.ranks = ranks;
  const bool slabs = SlabFft::available();
  const double cells = static_cast<double>(s.cells.size());
  const double wall_nodes = s.vessel ? static_cast<double>(s.vessel->surface.num_points()) : 0.0;
  const bool double_layer = s.c.domain.viscosity_ratio != 1.0;
  if (cells > 0) {
    const double N = s.grids->order;
    const double P = s.grids->n_grid->grid().size();
    const int radial = s.options.quadrature.radial_points > 0 ? s.options.quadrature.radial_points
                                                               : default_radial_points(s.grids->order);
    const double Q = 2.0 * radial * radial;
    const double H = s.tube_hematocrit.value_or(0.0);
    m.parts.push_back({"cells' geometry", cells * (2 * (2 * N + 1) * 4 * N * 96 + 56 * P), 1.0});
    const EwaldSum* e = find_sum(s, "cells, double layer");
    if (double_layer) {
      // Node entries hold the patch nodes beyond the fold radius, min(r_c, half the box's
      // smallest side), and within the cutoff (singular_quadrature.h NodeShares): none when the
      // box is at least twice the cutoff across; all of the patch's in free space.
      const double side = std::min({s.c.domain.box[0], s.c.domain.box[1], s.c.domain.box[2]});
      const double node_entries = !e || e->choice.parameters.cutoff > 0.5 * side ? 1.0 : 0.0;
      m.parts.push_back({"singular corrections", cells * (P * Q * 24 + node_entries * 2.3 * P * P), 1.0});
      const double near_targets = P * std::max(0.05, 2.0 * H);
      m.parts.push_back({"nearly-singular corrections", cells * near_targets * (Q * 36 + node_entries * 2250), 1.0});
    }
    if (e) {
      const double nodes = cells * P;
      const double volume = s.lumen_volume.value_or(s.c.domain.box[0] * s.c.domain.box[1] * s.c.domain.box[2]);
      const double rc = e->choice.parameters.cutoff;
      const double pairs = nodes * (4.0 * std::numbers::pi / 3.0) * rc * rc * rc * nodes / volume;
      const auto& K = e->choice.parameters.grid;
      // The plans keep them only within their bound (each rank's plan holds its sources' pairs).
      m.kept_coefficients = pairs / ranks <= static_cast<double>(s.options.domain.max_kept_pairs) ? 16 * pairs : 0.0;
      const double split_bytes = 2.2 * pairs + m.kept_coefficients + nodes * (4.1 * P + 250);
      const double spectra = 16.0 * K[0] * K[1] * (K[2] / 2 + 1);  // of one grid
      const double work_arrays = 6 * spectra;                         // two arrays of 3 grids
      m.lean_transforms = 2 * spectra;  // one of them of 1 grid (SpmePlan::transform_lean)
      const double split = split_bytes + (slabs ? kSplitEwaldWorkArrays * work_arrays : 0.0);
      m.parts.push_back({"cells' Ewald sum", split_bytes + work_arrays, split / (split_bytes + work_arrays)});
    }
  }
  if (wall_nodes > 0) {
    m.parts.push_back({"wall", 54.9e3 * wall_nodes, slabs ? kSplitWall : kSplitWallWithoutSlabs});
    // U and C of the recycled Krylov space, each rank its segment of the nodes (wall_solver.h).
    m.parts.push_back({"wall recycled space", 48.0 * s.options.wall_solve.recycle * wall_nodes, 1.0});
    if (cells > 0) {
      m.parts.push_back({"cells <-> wall", 17.0e3 * wall_nodes + 1.7e3 * cells * s.grids->n_grid->grid().size(),
                         kSplitCoupling});
    }
  }
  return m;
}

double memory_budget(const Case& c, int ranks_per_machine) {
  double machine = std::numeric_limits<double>::infinity();  // not known: no budget
  if (c.solver.memory_gib) {
    machine = *c.solver.memory_gib * kGiB;
  } else if (const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE); pages > 0 && page > 0) {
    machine = static_cast<double>(pages) * static_cast<double>(page);
  }
  return machine / std::max(1, ranks_per_machine);
}

namespace {

// Memory is short: what the steps free goes back to the system, so that the peak is closer to
// what a step holds, and the double layer's transforms go lean.
void spend_as_returned(Scenario& s) {
  s.memory.peak_factor = MemoryEstimate::kPeakFactorReturned;
  if (s.memory.lean_transforms > 0) {
    for (MemoryEstimate::Part& p : s.memory.parts)
      if (p.name == "cells' Ewald sum") p.bytes -= s.memory.lean_transforms;
    s.options.domain.lean_transforms = true;
  }
}

[[noreturn]] void refuse(const Scenario& s, RankLayout layout, double needed) {
  std::string parts;
  for (const MemoryEstimate::Part& p : s.memory.parts)
    parts += (parts.empty() ? "" : ", ") + p.name + " " + gib(s.memory.on_each_rank(p));
  const bool ranks = layout.ranks > 1;
  const std::string budget = s.c.solver.memory_gib ? "solver.memory_gib" : "the machine's memory";
  throw case_error(s.c, "solver.memory_gib",
                   "the run needs about " + gib(needed) + (ranks ? " on each of its ranks" : "") + " at its peak (" +
                       parts + "), more than the memory budget of " + gib(s.memory_budget) +
                       (ranks ? " per rank (" + budget + " shared by " + std::to_string(layout.per_machine) + " ranks)"
                              : s.c.solver.memory_gib ? "" : " (the machine's memory)") +
                       "; use fewer cells (a shorter period or a lower hematocrit), a smaller cells.order, "
                       "a coarser wall (vessel.element_size), " +
                       (ranks ? "fewer ranks on each machine, or machines with more memory" : "or a machine with more memory"));
}

}  // namespace

void apply_memory_budget(Scenario& s, RankLayout layout) {
  s.memory = estimate_memory(s, layout.ranks);
  s.memory_budget = s.options.domain.ranks.min(memory_budget(s.c, layout.per_machine));
  s.ranks_per_machine = layout.per_machine;
  s.reuses_freed_memory = s.memory.total() <= kReuseFreedMemory * s.memory_budget;
  if (!s.reuses_freed_memory) spend_as_returned(s);
  const double total = s.memory.total();
  if (total <= s.memory_budget) return;
  const double without = total - s.memory.peak_factor * s.memory.kept_coefficients / layout.ranks;
  if (s.memory.kept_coefficients > 0 && without <= s.memory_budget) {
    s.options.domain.max_kept_pairs = 0;
    s.keeps_pair_coefficients = false;
    return;
  }
  refuse(s, layout, without);
}

void estimate_memory_without_kept_pairs(Scenario& s, RankLayout layout) {
  s.memory = estimate_memory(s, layout.ranks);
  if (!s.reuses_freed_memory) spend_as_returned(s);
  if (s.memory.total() > s.memory_budget) refuse(s, layout, s.memory.total());
}

}  // namespace rbcflow
