#pragma once
// The pieces of the _rbcflow extension module (module.cpp): each binds one layer's calls.
#include <pybind11/pybind11.h>

namespace rbcflow::python {

// Case files as nested dicts, and the same validation as rbcflow check (case_bindings.cpp).
void bind_case(pybind11::module_& m);
// A run driven step by step (simulation_bindings.cpp).
void bind_simulation(pybind11::module_& m);
// A finished run's tables and frames (run_reading.cpp).
void bind_run_reading(pybind11::module_& m);

}  // namespace rbcflow::python
