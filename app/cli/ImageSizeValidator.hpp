#pragma once
// The CLI11 validator every `--size WxH` option shares (a usage error, exit 2, otherwise).
#include <CLI/CLI.hpp>

namespace reftrack::app {

CLI::Validator imageSizeValidator();

}  // namespace reftrack::app
