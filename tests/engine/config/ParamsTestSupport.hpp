#pragma once
// Shared by the parameter-struct tests: YAML text -> FileStorage, a write/read round trip, and
// (ErrorMessage.hpp) the message of a throw.
#include <opencv2/core.hpp>
#include <string>

#include "ErrorMessage.hpp"

namespace reftrack::test {

inline cv::FileStorage parseYaml(const std::string& yaml) {
  return cv::FileStorage("%YAML:1.0\n" + yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
}

// Writes a section with `write` and reads it back into `out`.
template <class Params>
void roundTrip(const Params& in, Params& out) {
  cv::FileStorage w(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  w << "s"
    << "{";
  in.write(w);
  w << "}";
  const std::string text = w.releaseAndGetString();
  cv::FileStorage r(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  out.read(r["s"]);
}

}  // namespace reftrack::test
