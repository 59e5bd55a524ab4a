#include "app/commands/Commands.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
CommandRegistration registerSimulateCommand(CLI::App& parent) {
  CLI::App* sub = parent.add_subcommand("simulate", "Render a ground-truth sequence of the synthetic scene");
  return {sub, [] { throw Error("simulate: under construction"); }};
}
const CommandRegistrar registrar(10, registerSimulateCommand);
}  // namespace

}  // namespace reftrack::app
