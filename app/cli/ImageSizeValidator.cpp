#include "app/cli/ImageSizeValidator.hpp"

#include "app/simulator/SimulationOptions.hpp"

namespace reftrack::app {

CLI::Validator imageSizeValidator() {
  return CLI::Validator(
      [](std::string& text) {
        return parseImageSize(text) ? std::string()
                                    : "expected WIDTHxHEIGHT, for example 640x480, got " + text;
      },
      "WxH");
}

}  // namespace reftrack::app
