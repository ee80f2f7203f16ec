#include "step_cases.h"

#include <Eigen/Geometry>
#include <exception>
#include <filesystem>
#include <stdexcept>

#include "geometry/surface/reference_shapes.h"
#include "geometry/vessel/vessel.h"
#include "io/case.h"
#include "libsolver/membrane/membrane_law.h"
#include "scenario/scenario.h"

namespace rbcflow::bench {

namespace {

constexpr double kDt = 1e-3;

struct Spec {
  int order = 12, dealias_order = 24;
  double lambda = 1.0;
  std::vector<SHSurface> cells;
};

std::unique_ptr<CellStepper> make(const Spec& spec, CellStepperOptions o) {
  auto grids = CellGrids::make(spec.order, spec.dealias_order);
  const std::shared_ptr<const MembraneLaw> law = make_membrane_law("skalak", 12.4, 200.0);
  std::vector<Cell> cells;
  for (const SHSurface& s : spec.cells) {
    Cell c;
    c.membrane = std::make_shared<const Membrane>(s, grids, MembraneParameters{law, 0.0669});
    c.shape = s;
    cells.push_back(std::move(c));
  }
  o.dt = kDt;
  o.viscosity_ratio = spec.lambda;
  return std::make_unique<CellStepper>(std::move(cells), grids, std::move(o));
}

SHSurface placed(const SHSurface& reference, const Eigen::Vector3d& axis, const Eigen::Vector3d& position) {
  SHSurface s = reference;
  s.rotate(Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), axis.normalized()).toRotationMatrix());
  s.translate(position);
  return s;
}

std::unique_ptr<CellStepper> single() {
  Spec spec{16, 48, 5.0, {}};
  spec.cells.push_back(placed(make_biconcave(16), Eigen::Vector3d(1, 0, 1), Eigen::Vector3d::Zero()));
  CellStepperOptions o;
  o.background = [](const Eigen::Vector3d& x) { return Eigen::Vector3d(x.z(), 0, 0); };
  return make(spec, std::move(o));
}

std::unique_ptr<CellStepper> minicase() {
  const Eigen::Vector3d box(10.5, 10.5, 8.0);
  TubeSpec tube_spec{10.0, 2, box, 0.5};
  Spec spec{12, 36, 1.0, {}};
  const SHSurface rbc = make_biconcave(12);
  spec.cells.push_back(placed(rbc, Eigen::Vector3d(0.2, 0, 1), Eigen::Vector3d(4.5, 5.25, 2.0)));
  spec.cells.push_back(placed(rbc, Eigen::Vector3d(0, 0.3, 1), Eigen::Vector3d(6.2, 5.0, 6.0)));
  CellStepperOptions o;
  o.domain.box = PeriodicBox(box);
  o.domain.ewald_tolerance = 1e-6;
  o.mean_velocity = Eigen::Vector3d(0, 0, 1);
  o.wall = std::make_shared<const WallElements>(tube(tube_spec));
  o.wall_solve.tolerance = 1e-6;
  return make(spec, std::move(o));
}

// data/cases/tube_27_cells.toml with `count` cells at its tube hematocrit: the period grows with
// the count (13.33 for 27 cells), the cells placed by the same code as rbcflow run's.
std::unique_ptr<CellStepper> tube_cells(int count) {
  Case c = read_case(std::filesystem::path(RBCFLOW_CASES_DIR) / "tube_27_cells.toml");
  c.domain.box[2] = 13.33 * count / 27.0;
  c.cells->hematocrit.reset();
  c.cells->count = count;
  c.time.dt = kDt;
  Scenario s = prepare_scenario(c);
  return make_stepper(s);
}

}  // namespace

std::unique_ptr<CellStepper> make_step_case(const std::string& name) {
  if (name == "single") return single();
  if (name == "minicase") return minicase();
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
