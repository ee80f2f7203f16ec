#include "scenario/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include "libsolver/quadrature/singular_quadrature.h"
#include "scenario/scenario.h"

namespace rbcflow {

namespace {

constexpr double kPeakFactor = 1.3;
constexpr double kProgramBytes = 60e6;
constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

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

double MemoryEstimate::total() const {
  double sum = 0;
  for (const Part& p : parts) sum += p.bytes;
  return kPeakFactor * sum + kProgramBytes;
}

MemoryEstimate estimate_memory(const Scenario& s) {
  MemoryEstimate m;
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
    m.parts.push_back({"cells' geometry", cells * (2 * (2 * N + 1) * 4 * N * 96 + 56 * P)});
    if (double_layer) {
      m.parts.push_back({"singular corrections", cells * (P * Q * 24 + 2.3 * P * P)});
      const double near_targets = P * std::max(0.05, 2.0 * H);
      m.parts.push_back({"nearly-singular corrections", cells * near_targets * (Q * 64 + 2250)});
    }
    if (const EwaldSum* e = find_sum(s, "cells, double layer")) {
      const double nodes = cells * P;
      const double volume = s.lumen_volume.value_or(s.c.domain.box[0] * s.c.domain.box[1] * s.c.domain.box[2]);
      const double rc = e->choice.parameters.cutoff;
      const double pairs = nodes * (4.0 * std::numbers::pi / 3.0) * rc * rc * rc * nodes / volume;
      const auto& K = e->choice.parameters.grid;
      m.kept_coefficients = 16 * pairs;
      m.parts.push_back({"cells' Ewald sum", 6 * pairs + m.kept_coefficients + nodes * (8.3 * P + 250) +
                                                 120.0 * K[0] * K[1] * K[2]});
    }
  }
  if (wall_nodes > 0) {
    m.parts.push_back({"wall", 72.5e3 * wall_nodes});
    if (cells > 0) m.parts.push_back({"cells <-> wall", 21.5e3 * wall_nodes + 5.2e3 * cells * s.grids->n_grid->grid().size()});
  }
  return m;
}

double memory_budget(const Case& c) {
  if (c.solver.memory_gib) return *c.solver.memory_gib * kGiB;
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0) return std::numeric_limits<double>::infinity();  // not known: no budget
  return static_cast<double>(pages) * static_cast<double>(page);
}

void apply_memory_budget(Scenario& s) {
  s.memory = estimate_memory(s);
  s.memory_budget = memory_budget(s.c);
  const double total = s.memory.total();
  if (total <= s.memory_budget) return;
  const double without = total - kPeakFactor * s.memory.kept_coefficients;
  if (s.memory.kept_coefficients > 0 && without <= s.memory_budget) {
    s.options.domain.max_kept_pairs = 0;
    s.keeps_pair_coefficients = false;
    return;
  }
  std::string parts;
  for (const MemoryEstimate::Part& p : s.memory.parts) parts += (parts.empty() ? "" : ", ") + p.name + " " + gib(p.bytes);
  throw case_error(s.c, "solver.memory_gib",
                   "the run needs about " + gib(without) + " at its peak (" + parts +
                       "), more than the memory budget of " + gib(s.memory_budget) +
                       (s.c.solver.memory_gib ? "" : " (the machine's memory)") +
                       "; use fewer cells (a shorter period or a lower hematocrit), a smaller cells.order, "
                       "a coarser wall (vessel.element_size), or a machine with more memory");
}

}  // namespace rbcflow
