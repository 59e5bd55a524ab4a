#include "engine/config/ParamFields.hpp"

#include <algorithm>

#include "engine/core/Error.hpp"

namespace reftrack {

void OneOf::check(const std::string& name, const std::string& value) const {
  if (std::find(words.begin(), words.end(), value) != words.end()) return;
  std::string list;
  for (const std::string& w : words) list += (list.empty() ? "" : ", ") + w;
  throw Error("parameter '" + name + "' must be one of " + list + "; got '" + value + "'");
}

void OddRange::check(const std::string& name, const int& value) const {
  requireIntInRange(name, value, lo, hi);
  if (value % 2 == 0) throw Error("parameter '" + name + "' must be odd");
}

void OffOrRange::check(const std::string& name, const int& value) const {
  if (value != 0) requireIntInRange(name, value, lo, hi);
}

}  // namespace reftrack
