#pragma once
// Shared by the parameter-struct tests: YAML text -> FileStorage, and the message of a throw.
#include <functional>
#include <opencv2/core.hpp>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::test {

inline cv::FileStorage parseYaml(const std::string& yaml) {
  return cv::FileStorage("%YAML:1.0\n" + yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
}

inline std::string errorMessage(const std::function<void()>& f) {
  try {
    f();
  } catch (const reftrack::Error& e) {
    return e.what();
  }
  return "(no error)";
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
