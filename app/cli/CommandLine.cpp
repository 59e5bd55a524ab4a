#include "app/cli/CommandLine.hpp"

#include <iostream>
#include <opencv2/core.hpp>

#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

int runCommandLine(int argc, char** argv) {
  CLI::App app{"reftrack: marker-less AR camera tracking against calibrated reference images"};
  app.set_version_flag("--version", std::string("reftrack ") + REFTRACK_VERSION);
  app.require_subcommand(1);
  app.fallthrough(false);

  std::vector<CommandRegistration> commands = {
      registerSimulateCommand(app),
  };

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

  for (CommandRegistration& c : commands) {
    if (!c.subcommand->parsed()) continue;
    try {
      c.action();
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
