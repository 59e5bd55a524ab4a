#pragma once
// TrackerParamsArgument: the `params` a Python caller gives the Tracker — None (the defaults), a
// YAML file's path (str or os.PathLike; the `--params` file of the commands) or a dict of the
// same sections ({"ransac": {"max_iterations": 80}}) — as TrackerParams, checked as a file is: an
// unknown key or a bad value raises reftrack.Error naming it.
#include <pybind11/pybind11.h>

#include "engine/config/TrackerParams.hpp"

namespace reftrack::python {

TrackerParams trackerParamsFrom(const pybind11::object& params);

// The dict as the YAML (flow style) TrackerParams::parse reads; raises TypeError naming a value
// that is not None, a boolean, a number, text, a dict with text keys or a list.
std::string yamlOfDict(const pybind11::dict& params);

}  // namespace reftrack::python
