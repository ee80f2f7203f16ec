// _rbcflow: the compiled part of the Python module `rbcflow` (python/rbcflow/__init__.py is the
// rest). Errors: bad input (a case, a checkpoint, a mesh: what the command line answers with
// exit status 2) raises rbcflow.CaseError, a ValueError; a failure during a run (exit status 1)
// raises rbcflow.RunError, a RuntimeError; each with the message the command line prints.
#include <pybind11/pybind11.h>

#include <stdexcept>

#include "bindings.h"
#include "io/input_error.h"

namespace py = pybind11;

PYBIND11_MODULE(_rbcflow, m) {
  m.doc() = "rbcflow: red blood cells in Stokes flow by the spectral boundary integral method";
  static py::exception<rbcflow::InputError> case_error(m, "CaseError", PyExc_ValueError);
  static py::exception<std::runtime_error> run_error(m, "RunError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const py::builtin_exception&) {
      throw;  // IndexError, ValueError, ... raised by the bindings themselves
    } catch (const rbcflow::InputError& e) {
      case_error(e.what());
    } catch (const std::runtime_error& e) {
      run_error(e.what());
    }
  });
  rbcflow::python::bind_case(m);
  rbcflow::python::bind_simulation(m);
  rbcflow::python::bind_run_reading(m);
}
