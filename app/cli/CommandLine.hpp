#pragma once
// The `reftrack <subcommand>` command line. Exit codes: 0 success, 1 runtime failure (one clear
// message on stderr), 2 usage error (unknown option, bad value, missing argument).
#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace reftrack::app {

// A subcommand registers its options on `parent` and returns the action to run when chosen.
using CommandAction = std::function<void()>;

struct CommandRegistration {
  CLI::App* subcommand = nullptr;
  CommandAction action;
};

int runCommandLine(int argc, char** argv);

}  // namespace reftrack::app
