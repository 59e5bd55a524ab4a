#include "app/cli/CameraEffectsValidator.hpp"

#include "app/simulator/CameraEffects.hpp"
#include "engine/core/Error.hpp"

namespace reftrack::app {

CLI::Validator cameraEffectsValidator() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          cameraEffectsFor(text, {640, 480});
          return std::string();
        } catch (const Error& e) {
          return std::string(e.what());
        }
      },
      "EFFECTS");
}

}  // namespace reftrack::app
