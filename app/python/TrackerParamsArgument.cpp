#include "TrackerParamsArgument.hpp"

#include <pybind11/stl/filesystem.h>

#include <cmath>
#include <filesystem>
#include <string>

namespace py = pybind11;

namespace reftrack::python {

namespace {

std::string quoted(const py::handle& text) {
  // JSON's double-quoted string is YAML's too (escapes included).
  return py::str(py::module_::import("json").attr("dumps")(text));
}

std::string yamlOf(const py::handle& value, const std::string& name) {
  if (value.is_none()) return "null";
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return quoted(value);
  if (py::isinstance<py::dict>(value)) {
    std::string out = "{";
    for (const auto& [key, item] : py::reinterpret_borrow<py::dict>(value)) {
      if (!py::isinstance<py::str>(key))
        throw py::type_error("parameters: the keys of " + (name.empty() ? "the dict" : name) +
                             " must be text, got " + std::string(py::repr(key)));
      const std::string k = key.cast<std::string>();
      out += (out.size() > 1 ? ", " : "") + quoted(key) + ": " +
             yamlOf(item, name.empty() ? k : name + "." + k);
    }
    return out + "}";
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    std::string out = "[";
    std::size_t i = 0;
    for (const py::handle item : value) {
      out += (i ? ", " : "") + yamlOf(item, name + "[" + std::to_string(i) + "]");
      ++i;
    }
    return out + "]";
  }
  if (py::hasattr(value, "__index__"))  // int, numpy integers
    return py::str(py::int_(py::reinterpret_borrow<py::object>(value)));
  if (py::hasattr(value, "__float__")) {  // float, numpy floats
    const double v = py::float_(py::reinterpret_borrow<py::object>(value)).cast<double>();
    if (std::isnan(v)) return ".nan";
    if (std::isinf(v)) return v > 0 ? ".inf" : "-.inf";
    return py::repr(py::float_(v));
  }
  throw py::type_error("parameters: " + name + " is a " +
                       std::string(py::str(py::type::of(value).attr("__name__"))) +
                       "; give None, booleans, numbers, text, dicts or lists");
}

}  // namespace

std::string yamlOfDict(const py::dict& params) { return yamlOf(params, ""); }

TrackerParams trackerParamsFrom(const py::object& params) {
  if (params.is_none()) return TrackerParams{};
  if (py::isinstance<py::dict>(params))
    return TrackerParams::parse(yamlOfDict(params), "parameters (dict)");
  if (py::isinstance<py::str>(params) || py::hasattr(params, "__fspath__"))
    return TrackerParams::load(params.cast<std::filesystem::path>());
  throw py::type_error("params must be None, a YAML file's path or a dict, got " +
                       std::string(py::str(py::type::of(params).attr("__name__"))));
}

}  // namespace reftrack::python
