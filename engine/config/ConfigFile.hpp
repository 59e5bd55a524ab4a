#pragma once
// ConfigFile: opens a user-written OpenCV YAML/XML/JSON file for reading. OpenCV recognises YAML
// only by its `%YAML:1.0` first line; a file without it (hand-written YAML) is read as if it had
// it, instead of failing as malformed XML.
#include <filesystem>
#include <opencv2/core.hpp>
#include <string>

namespace reftrack {

// `text` with "%YAML:1.0\n" in front unless it already starts (after a UTF-8 byte-order mark)
// with a %YAML directive, or is XML ('<') or JSON ('{').
std::string withYamlDirective(const std::string& text);

// Parses `text` (withYamlDirective applied). Throws reftrack::Error "<what> <invalid>: <OpenCV's
// reason>" when OpenCV cannot parse it, and "<what>: <key> is not a valid matrix: ..." when an
// OpenCV matrix's header (rows, cols, dt) disagrees with its data (which OpenCV would allocate
// before checking).
cv::FileStorage openConfigText(const std::string& text, const std::string& what,
                               const std::string& invalid = "is not valid OpenCV YAML/XML");

// Reads `file` and parses it as openConfigText does; an unreadable file throws
// "<what> cannot be read". The caller reports a missing file in its own words first.
cv::FileStorage openConfigFile(const std::filesystem::path& file, const std::string& what,
                               const std::string& invalid = "is not valid OpenCV YAML/XML");

}  // namespace reftrack
