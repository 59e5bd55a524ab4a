#pragma once
// The CLI11 validator every `--effects LIST` option shares: none, webcam or a comma-separated
// list of cameraEffectNames() (a usage error, exit 2, otherwise).
#include <CLI/CLI.hpp>

namespace reftrack::app {

CLI::Validator cameraEffectsValidator();

}  // namespace reftrack::app
