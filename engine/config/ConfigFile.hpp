#pragma once
// ConfigFile: reads a user-written YAML file — parameters, camera.yml, motion.yml, labels,
// map.yml, EuRoC's sensor.yaml — into a YamlNode tree (YamlTree.hpp: YAML 1.2 by yaml-cpp, with
// or without the `%YAML:1.0` line OpenCV writes). Every reader of a user's YAML opens it here.
#include <filesystem>
#include <string>

#include "engine/config/YamlNode.hpp"

namespace reftrack {

// Parses `text`; the root is a map, or null when the text holds no value (an empty file: every
// key absent). Throws reftrack::Error "<what> <invalid>: line <n>: <what is wrong>" when it is
// not valid YAML, and "<what> must hold a map of key: value at the top level" when its root is a
// list or a single value.
YamlNode readConfigText(const std::string& text, const std::string& what,
                        const std::string& invalid = "is not valid YAML");

// Reads `file` and parses it as readConfigText does; an unreadable file throws
// "<what> cannot be read". The caller reports a missing file in its own words first.
YamlNode readConfigFile(const std::filesystem::path& file, const std::string& what,
                        const std::string& invalid = "is not valid YAML");

}  // namespace reftrack
