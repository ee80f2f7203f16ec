// A finished (or running) run read back for rbcflow.read_run: its CSV tables as columns of
// numbers, and its XDMF frames as numpy arrays (io/csv.h, io/xdmf_reader.h).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bindings.h"
#include "io/csv.h"
#include "io/xdmf_reader.h"

namespace py = pybind11;

namespace rbcflow::python {
namespace {

template <typename Matrix>
py::array_t<typename Matrix::Scalar> to_numpy(const Matrix& m, bool flat) {
  using T = typename Matrix::Scalar;
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(m.rows())};
  if (!flat) shape.push_back(static_cast<py::ssize_t>(m.cols()));
  py::array_t<T> a(shape);
  T* out = a.mutable_data();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) out[i * m.cols() + j] = m(i, j);
  return a;
}

// Every column as a float array; an empty field is NaN.
py::dict read_table(const std::string& path) {
  const CsvTable t = read_csv(path);
  py::dict out;
  for (std::size_t k = 0; k < t.columns.size(); ++k) {
    py::array_t<double> column(static_cast<py::ssize_t>(t.rows.size()));
    double* x = column.mutable_data();
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const std::string& field = t.rows[r][k];
      x[r] = field.empty() ? std::nan("") : std::stod(field);
    }
    out[py::str(t.columns[k])] = column;
  }
  return out;
}

py::dict read_frame(const std::string& dir, long step) {
  const XdmfFrame f = read_xdmf_frame(dir, step);
  py::dict out;
  out["step"] = f.step;
  out["time"] = f.time;
  for (const Surface& s : f.surfaces) {
    py::dict surface;
    surface["points"] = to_numpy(s.mesh.points, false);
    surface["triangles"] = to_numpy(s.mesh.triangles, false);
    for (const SurfaceField& field : s.fields) surface[py::str(field.name)] = to_numpy(field.values, field.values.cols() == 1);
    out[py::str(s.name)] = surface;
  }
  return out;
}

}  // namespace

void bind_run_reading(py::module_& m) {
  m.def("_read_table", &read_table, py::arg("path"));
  m.def(
      "_frames",
      [](const std::string& dir) {
        std::vector<std::pair<long, double>> out;
        for (const XdmfFrameTime& f : read_xdmf_frames(dir)) out.emplace_back(f.step, f.time);
        return out;
      },
      py::arg("dir"));
  m.def("_frame", &read_frame, py::arg("dir"), py::arg("step"));
}

}  // namespace rbcflow::python
