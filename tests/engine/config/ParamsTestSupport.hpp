#pragma once
// Shared by the parameter-struct tests: YAML text -> its root YamlNode (as a user's file is read),
// a write/read round trip, and (ErrorMessage.hpp) the message of a throw.
#include <opencv2/core.hpp>
#include <string>

#include "ErrorMessage.hpp"
#include "engine/config/ConfigFile.hpp"
#include "engine/config/YamlNode.hpp"

namespace reftrack::test {

inline YamlNode parseYaml(const std::string& yaml) { return readConfigText(yaml, "test YAML"); }

// Writes a section with `write` (OpenCV's FileStorage, as the program saves it) and reads it
// back into `out` (as a user's file is read).
template <class Params>
void roundTrip(const Params& in, Params& out) {
  cv::FileStorage w(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  w << "s"
    << "{";
  in.write(w);
  w << "}";
  out.read(parseYaml(w.releaseAndGetString())["s"]);
}

}  // namespace reftrack::test
