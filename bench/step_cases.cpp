#include "step_cases.h"

#include <exception>
#include <filesystem>
#include <stdexcept>

#include "io/case.h"
#include "scenario/scenario.h"

namespace rbcflow::bench {

namespace {

namespace fs = std::filesystem;

constexpr double kDt = 1e-3;

StepCase from_case(Case c, double memory_gib, bool fixed_dt = true) {
  if (fixed_dt) c.time.dt = kDt;
  if (memory_gib > 0) c.solver.memory_gib = memory_gib;
  Scenario s = prepare_scenario(c);
  const double estimate = s.memory.total();
  return {make_stepper(s), estimate};
}

// A data/cases tube case with `count` cells at its tube hematocrit: the period grows with the
// count (`period` for `cells` cells), the cells placed by the same code as rbcflow run's.
StepCase tube_cells(const char* file, double period, int cells, int count, double memory_gib) {
  Case c = read_case(fs::path(RBCFLOW_CASES_DIR) / file);
  c.domain.box[2] = period * count / cells;
  c.cells->hematocrit.reset();
  c.cells->count = count;
  return from_case(std::move(c), memory_gib);
}

// The K of a name "<prefix>K", or 0.
int count_in(const std::string& name, const std::string& prefix) {
  if (!name.starts_with(prefix)) return 0;
  std::size_t used = 0;
  int count = 0;
  try {
    count = std::stoi(name.substr(prefix.size()), &used);
  } catch (const std::exception&) {
  }
  return count >= 1 && prefix.size() + used == name.size() ? count : 0;
}

}  // namespace

StepCase make_step_case(const std::string& name, double memory_gib) {
  if (name == "single" || name == "minicase") {
    return from_case(read_case(fs::path(RBCFLOW_BENCH_CASES_DIR) / (name + ".toml")), memory_gib);
  }
  // tubeK: data/cases/tube_27_cells.toml's D = 6 tube; wideK: tube_1000_cells.toml's D = 12.
  if (const int count = count_in(name, "tube")) return tube_cells("tube_27_cells.toml", 13.33, 27, count, memory_gib);
  if (const int count = count_in(name, "wide")) return tube_cells("tube_1000_cells.toml", 123.56, 1000, count, memory_gib);
  // Any case file, with its own time step.
  if (name.ends_with(".toml")) return from_case(read_case(name), memory_gib, false);
  throw std::invalid_argument("unknown case '" + name +
                              "' (single, minicase, tubeK, wideK: K cells in the D = 6 or D = 12 tube, e.g. tube27; "
                              "or a case file CASE.toml)");
}

}  // namespace rbcflow::bench
