// rbcflow.Simulation: scenario::Run driven step by step from Python, writing its output
// directory exactly as `rbcflow run` does. Steps run without the GIL; Ctrl-C is seen between
// steps, so an interrupted run leaves every step it finished written.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>

#include "bindings.h"
#include "geometry/sph/sph_transform.h"
#include "io/output_dir.h"
#include "scenario/checkpoint.h"
#include "scenario/run.h"

namespace py = pybind11;

namespace rbcflow::python {
namespace {

namespace fs = std::filesystem;

// A numpy array that owns a copy of `m` (rows x cols, C order).
py::array_t<double> to_numpy(const Eigen::MatrixXd& m) {
  py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto view = a.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return a;
}

class Simulation {
 public:
  explicit Simulation(RunRequest request) {
    check_output_dir(request.c, request.c.output.dir);
    check_run_directory(request, "overwrite=True", "Simulation.from_checkpoint");
    request.quiet = true;
    py::gil_scoped_release unlocked;
    run_ = std::make_unique<Run>(std::move(request));
  }

  void step(long n) {
    for (long i = 0; i < n; ++i) {
      {
        py::gil_scoped_release unlocked;
        run_->step();
      }
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    }
  }

  void run() {
    while (!run_->done()) step(1);
    py::gil_scoped_release unlocked;
    run_->finish();
  }

  double time() const { return run_->stepper().time(); }
  long steps_done() const { return run_->stepper().steps(); }
  long last_step() const { return run_->last_step(); }
  std::string out() const { return run_->c().output.dir.string(); }
  long cell_count() const { return static_cast<long>(run_->stepper().cells().size()); }

  py::array_t<double> cell_nodes(long i) const {
    const Cell& cell = this->cell(i);
    return to_numpy(cell.shape.geometry(*run_->stepper().grids().n_grid).x);
  }

  py::array_t<double> cell_centroids() const {
    const CellStepper& s = run_->stepper();
    const std::vector<Eigen::Vector3d> x = s.volume_centroids();  // none for walls alone
    Eigen::MatrixXd out(x.size(), 3);
    for (std::size_t c = 0; c < x.size(); ++c) out.row(c) = x[c].transpose();
    return to_numpy(out);
  }

  // The area-weighted mean surface velocity of each cell over the last step (cells.csv's
  // velocity); NaN before the first step.
  py::array_t<double> cell_velocities() const {
    const CellStepper& s = run_->stepper();
    Eigen::MatrixXd out = Eigen::MatrixXd::Constant(s.cells().size(), 3, std::nan(""));
    if (!s.cells().empty() && s.velocity().size()) {
      const int np = s.grids().n_grid->grid().size();
      for (std::size_t c = 0; c < s.cells().size(); ++c) {
        const SurfaceGeometry g = s.cells()[c].shape.geometry(*s.grids().n_grid);
        out.row(c) = (s.velocity().middleRows(c * np, np).transpose() * g.area_weight / g.area_weight.sum()).transpose();
      }
    }
    return to_numpy(out);
  }

  void checkpoint(const std::string& file) {
    py::gil_scoped_release unlocked;
    run_->checkpoint(file);
  }

 private:
  const Cell& cell(long i) const {
    const auto& cells = run_->stepper().cells();
    if (i < 0) i += static_cast<long>(cells.size());
    if (i < 0 || i >= static_cast<long>(cells.size())) {
      throw py::index_error("cell " + std::to_string(i) + " of " + std::to_string(cells.size()));
    }
    return cells[i];
  }

  std::unique_ptr<Run> run_;
};

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<Simulation>(m, "_Simulation")
      .def(py::init([](const std::string& text, const std::string& source, const std::string& out, bool overwrite) {
             RunRequest r;
             r.c = parse_case(text, source);
             r.c.output.dir = out;
             r.overwrite = overwrite;
             return std::make_unique<Simulation>(std::move(r));
           }),
           py::arg("text"), py::arg("source"), py::arg("out"), py::arg("overwrite"))
      .def_static(
          "from_checkpoint",
          [](const std::string& file, const std::string& out, bool overwrite) {
            RunRequest r;
            r.c = case_of_checkpoint(file);
            r.c.output.dir = out;
            r.restart = file;
            r.overwrite = overwrite;
            return std::make_unique<Simulation>(std::move(r));
          },
          py::arg("file"), py::arg("out"), py::arg("overwrite"))
      .def("step", &Simulation::step, py::arg("n") = 1)
      .def("run", &Simulation::run)
      .def_property_readonly("time", &Simulation::time)
      .def_property_readonly("steps_done", &Simulation::steps_done)
      .def_property_readonly("last_step", &Simulation::last_step)
      .def_property_readonly("out", &Simulation::out)
      .def_property_readonly("cell_count", &Simulation::cell_count)
      .def("cell_nodes", &Simulation::cell_nodes, py::arg("i"))
      .def("cell_centroids", &Simulation::cell_centroids)
      .def("cell_velocities", &Simulation::cell_velocities)
      .def("checkpoint", &Simulation::checkpoint, py::arg("file"));
}

}  // namespace rbcflow::python
