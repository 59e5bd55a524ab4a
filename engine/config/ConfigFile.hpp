#pragma once
// ConfigFile: opens a user-written YAML file for reading with OpenCV's FileStorage, after
// YamlSubsetValidator has checked that it keeps to the YAML subset reftrack writes (OpenCV 4.6's
// parser hangs on some texts outside it). The `%YAML:1.0` first line may be left out. Every
// reader of a user's YAML (parameters, camera.yml, motion.yml, labels, maps) opens it here.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

namespace reftrack {

// `text` without a UTF-8 byte-order mark, with "%YAML:1.0\n" in front unless it starts with a
// '%' directive line.
std::string withYamlDirective(const std::string& text);

// Parses `text` (withYamlDirective applied) as YAML. Throws reftrack::Error "<what> <invalid>: line
// <n>: <what is wrong>" when it leaves the subset, "<what> <invalid>: <OpenCV's reason>" when
// OpenCV cannot parse it, and "<what>: <key> is not a valid matrix: ..." when an
// OpenCV matrix's header (rows, cols, dt) disagrees with its data (which OpenCV would allocate
// before checking).
cv::FileStorage openConfigText(const std::string& text, const std::string& what,
                               const std::string& invalid = "is not valid YAML");

// Reads `file` and parses it as openConfigText does; an unreadable file throws
// "<what> cannot be read". The caller reports a missing file in its own words first.
cv::FileStorage openConfigFile(const std::filesystem::path& file, const std::string& what,
                               const std::string& invalid = "is not valid YAML");

}  // namespace reftrack
