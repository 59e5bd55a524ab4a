#pragma once
// Every subcommand of `reftrack` lives in one file — product commands under app/commands/, research
// commands (experiments, benchmarks) under app/research/commands/ — and registers itself with a
// file-scope CommandRegistrar; `reftrack --help` lists the product group first, each by `order`.
#include <utility>
#include <vector>

#include "app/cli/CommandLine.hpp"

namespace reftrack::app {

using CommandFactory = CommandRegistration (*)(CLI::App& parent);

enum class CommandGroup { Product, Research };

struct CommandRegistrar {
  CommandRegistrar(int order, CommandFactory factory, CommandGroup group = CommandGroup::Product);
};

struct RegisteredCommand {
  CommandFactory factory;
  CommandGroup group;
};

// All registered commands, product first, each group sorted by order.
std::vector<RegisteredCommand> registeredCommands();

// The heading of a group in `reftrack --help`.
const char* commandGroupHeading(CommandGroup group);

}  // namespace reftrack::app
