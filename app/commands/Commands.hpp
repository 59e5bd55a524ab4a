#pragma once
// Every subcommand of `reftrack`, one file each under app/commands/.
#include "app/cli/CommandLine.hpp"

namespace reftrack::app {

CommandRegistration registerSimulateCommand(CLI::App& parent);

}  // namespace reftrack::app
