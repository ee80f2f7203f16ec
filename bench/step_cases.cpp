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

StepCase from_case(Case c) {
  c.time.dt = kDt;
  Scenario s = prepare_scenario(c);
  const double estimate = s.memory.total();
  return {make_stepper(s), estimate};
}

// data/cases/tube_27_cells.toml with `count` cells at its tube hematocrit: the period grows with
// the count (13.33 for 27 cells), the cells placed by the same code as rbcflow run's.
StepCase tube_cells(int count) {
  Case c = read_case(fs::path(RBCFLOW_CASES_DIR) / "tube_27_cells.toml");
  c.domain.box[2] = 13.33 * count / 27.0;
  c.cells->hematocrit.reset();
  c.cells->count = count;
  return from_case(std::move(c));
}

}  // namespace

StepCase make_step_case(const std::string& name) {
  if (name == "single" || name == "minicase") {
    return from_case(read_case(fs::path(RBCFLOW_BENCH_CASES_DIR) / (name + ".toml")));
  }
  if (name.starts_with("tube")) {
    std::size_t used = 0;
    int count = 0;
    try {
      count = std::stoi(name.substr(4), &used);
    } catch (const std::exception&) {
    }
    if (count >= 1 && 4 + used == name.size()) return tube_cells(count);
  }
  throw std::invalid_argument("unknown case '" + name + "' (single, minicase, tubeK: K cells, e.g. tube27)");
}

}  // namespace rbcflow::bench
