#pragma once
// Every subcommand of `reftrack` lives in one file under app/commands/ and registers itself
// with a file-scope CommandRegistrar; `order` sets its place in `reftrack --help`.
#include <utility>
#include <vector>

#include "app/cli/CommandLine.hpp"

namespace reftrack::app {

using CommandFactory = CommandRegistration (*)(CLI::App& parent);

struct CommandRegistrar {
  CommandRegistrar(int order, CommandFactory factory);
};

// All registered factories, sorted by order.
std::vector<CommandFactory> registeredCommands();

}  // namespace reftrack::app
