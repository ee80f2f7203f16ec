// Case files as nested dicts: TOML text <-> Python objects with toml11 (the parser the command
// line uses), and the case validated by io's parser and, for check(), by prepare_scenario:
// exactly what `rbcflow check` reports.
#include <pybind11/stl.h>

#include <cstdint>
#include <map>
#include <sstream>
#include <string>
#include <toml.hpp>
#include <vector>

#include "bindings.h"
#include "io/case.h"
#include "io/output_dir.h"
#include "scenario/scenario.h"

namespace py = pybind11;

namespace rbcflow::python {
namespace {

// Tables keep their keys sorted (std::map): the same order every time a case is written.
using Value = toml::basic_value<toml::discard_comments, std::map, std::vector>;

py::object to_python(const Value& v) {
  switch (v.type()) {
    case toml::value_t::boolean: return py::bool_(v.as_boolean());
    case toml::value_t::integer: return py::int_(v.as_integer());
    case toml::value_t::floating: return py::float_(v.as_floating());
    case toml::value_t::string: return py::str(v.as_string().str);
    case toml::value_t::array: {
      py::list out;
      for (const Value& x : v.as_array()) out.append(to_python(x));
      return out;
    }
    case toml::value_t::table: {
      py::dict out;
      for (const auto& [key, x] : v.as_table()) out[py::str(key)] = to_python(x);
      return out;
    }
    default: break;
  }
  throw py::value_error("a case file holds no dates or times");
}

Value from_python(const py::handle& o, const std::string& where) {
  if (py::isinstance<py::bool_>(o)) return Value(o.cast<bool>());
  if (py::isinstance<py::int_>(o)) return Value(o.cast<std::int64_t>());
  if (py::isinstance<py::float_>(o)) return Value(o.cast<double>());
  if (py::isinstance<py::str>(o)) return Value(o.cast<std::string>());
  if (py::isinstance<py::dict>(o)) {
    typename Value::table_type table;
    for (const auto& [key, x] : o.cast<py::dict>()) {
      const std::string name = py::str(key);
      table.emplace(name, from_python(x, where.empty() ? name : where + "." + name));
    }
    return Value(table);
  }
  if (py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o)) {
    typename Value::array_type array;
    for (const py::handle x : o) array.push_back(from_python(x, where));
    return Value(array);
  }
  // numpy scalars and anything else with __float__ / __int__
  if (py::hasattr(o, "__index__")) return Value(o.attr("__index__")().cast<std::int64_t>());
  if (py::hasattr(o, "__float__")) return Value(o.attr("__float__")().cast<double>());
  if (py::hasattr(o, "tolist")) return from_python(o.attr("tolist")(), where);
  throw py::value_error(where + ": a case holds booleans, numbers, strings, lists and tables, not " +
                        std::string(py::str(o.get_type().attr("__name__"))));
}

// TOML text of a case given as a dict (the keys as written in case files).
std::string toml_text(const py::dict& d) {
  std::ostringstream out;
  out << from_python(d, "");
  return out.str();
}

}  // namespace

void bind_case(py::module_& m) {
  m.def(
      "_dict_from_toml",
      [](const std::string& text, const std::string& source) {
        parse_case(text, source);  // bad keys and values raise CaseError here, as rbcflow check reports them
        std::istringstream in(text);
        return to_python(toml::parse<toml::discard_comments, std::map, std::vector>(in, source));
      },
      py::arg("text"), py::arg("source"));
  m.def("_toml_from_dict", &toml_text, py::arg("case"));
  m.def(
      "_check",
      [](const std::string& text, const std::string& source) {
        const Case c = parse_case(text, source);
        py::gil_scoped_release unlocked;
        check_output_dir(c, c.output.dir);
        prepare_scenario(c);
      },
      py::arg("text"), py::arg("source"));
}

}  // namespace rbcflow::python
