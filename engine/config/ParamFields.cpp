#include "engine/config/ParamFields.hpp"

#include "engine/core/Error.hpp"

namespace reftrack {

void OddRange::check(const std::string& name, const int& value) const {
  requireIntInRange(name, value, lo, hi);
  if (value % 2 == 0) throw Error("parameter '" + name + "' must be odd");
}

void OffOrRange::check(const std::string& name, const int& value) const {
  if (value != 0) requireIntInRange(name, value, lo, hi);
}

}  // namespace reftrack
