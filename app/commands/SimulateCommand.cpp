#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

CommandRegistration registerSimulateCommand(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand("simulate", "Render a ground-truth sequence of the synthetic scene");
  return {sub, [] { throw Error("simulate: under construction"); }};
}

}  // namespace reftrack::app
