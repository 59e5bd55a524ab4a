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
std::vector<std::pair<int, CommandFactory>>& factoryTable() {
  static std::vector<std::pair<int, CommandFactory>> table;
  return table;
}
}  // namespace

CommandRegistrar::CommandRegistrar(int order, CommandFactory factory) {
  factoryTable().emplace_back(order, factory);
}

std::vector<CommandFactory> registeredCommands() {
  auto table = factoryTable();
  std::stable_sort(table.begin(), table.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<CommandFactory> out;
  for (const auto& entry : table) out.push_back(entry.second);
  return out;
}

int runCommandLine(int argc, char** argv) {
  CLI::App app{"reftrack: marker-less AR camera tracking against calibrated reference images"};
  app.set_version_flag("--version", std::string("reftrack ") + REFTRACK_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);

  std::vector<CommandRegistration> commands;
  for (CommandFactory factory : registeredCommands()) commands.push_back(factory(app));

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
