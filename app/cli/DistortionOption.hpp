#pragma once
// The `--distortion k1,k2,p1,p2[,k3]` option of the simulator-driven commands (OpenCV's
// coefficient order; a malformed list is a usage error, exit 2).
#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace reftrack::app {

// "-0.3,0.1,0,0" -> {-0.3, 0.1, 0, 0}; nullopt unless 4 or 5 finite numbers joined by commas.
std::optional<std::vector<double>> parseDistortion(const std::string& text);

// Adds --distortion to `command`, storing the coefficients in `target`.
CLI::Option* addDistortionOption(CLI::App* command, std::vector<double>& target);

}  // namespace reftrack::app
