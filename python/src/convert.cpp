#include "bindings.h"

namespace hoilcd::python {

py::object JsonToPython(const std::string& text) { return py::module_::import("json").attr("loads")(text); }

std::string PythonToJson(const py::handle& value) {
  return py::module_::import("json").attr("dumps")(value).cast<std::string>();
}

}  // namespace hoilcd::python
