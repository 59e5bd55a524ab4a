#include "app/cli/CommandLine.hpp"

#include <algorithm>
#include <csignal>
#include <iostream>
#include <opencv2/core.hpp>

#include "app/cli/Interruption.hpp"
#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
struct CommandEntry {
  int order;
  RegisteredCommand command;
};

std::vector<CommandEntry>& commandTable() {
  static std::vector<CommandEntry> table;
  return table;
}
}  // namespace

CommandRegistrar::CommandRegistrar(int order, CommandFactory factory, CommandGroup group) {
  commandTable().push_back({order, {factory, group}});
}

std::vector<RegisteredCommand> registeredCommands() {
  auto table = commandTable();
  std::stable_sort(table.begin(), table.end(), [](const CommandEntry& a, const CommandEntry& b) {
    return std::pair(a.command.group, a.order) < std::pair(b.command.group, b.order);
  });
  std::vector<RegisteredCommand> out;
  for (const CommandEntry& entry : table) out.push_back(entry.command);
  return out;
}

const char* commandGroupHeading(CommandGroup group) {
  return group == CommandGroup::Research
             ? "Research (the paper's experiments, benchmarks against baselines)"
             : "Commands";
}

int runCommandLine(int argc, char** argv) {
  CLI::App app{"reftrack: marker-less AR camera tracking against calibrated reference images"};
  app.set_version_flag("--version", std::string("reftrack ") + REFTRACK_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);

  std::vector<CommandRegistration> commands;
  for (const RegisteredCommand& registered : registeredCommands()) {
    commands.push_back(registered.factory(app));
    commands.back().subcommand->group(commandGroupHeading(registered.group));
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  installInterruptHandlers();
  for (CommandRegistration& c : commands) {
    if (!c.subcommand->parsed()) continue;
    try {
      c.action();
      if (const int signal = interruptSignal(); signal != 0) {
        std::cerr << "reftrack " << c.subcommand->get_name() << ": interrupted by "
                  << (signal == SIGINT ? "SIGINT" : "SIGTERM")
                  << "; outputs are complete up to the last frame handled\n";
        return 128 + signal;
      }
      return 0;
    } catch (const reftrack::Error& e) {
      std::cerr << "reftrack " << c.subcommand->get_name() << ": error: " << e.what() << "\n";
    } catch (const cv::Exception& e) {
      std::cerr << "reftrack " << c.subcommand->get_name() << ": OpenCV error: " << e.err << "\n";
    } catch (const std::exception& e) {
      std::cerr << "reftrack " << c.subcommand->get_name() << ": error: " << e.what() << "\n";
    }
    return 1;
  }
  return 2;
}

}  // namespace reftrack::app
