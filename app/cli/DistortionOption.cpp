#include "app/cli/DistortionOption.hpp"

#include <cmath>
#include <sstream>

namespace reftrack::app {

std::optional<std::vector<double>> parseDistortion(const std::string& text) {
  std::vector<double> values;
  std::stringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    std::size_t used = 0;
    double value = 0.0;
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
      return std::nullopt;
    }
    if (used != item.size() || !std::isfinite(value)) return std::nullopt;
    values.push_back(value);
  }
  if (!text.empty() && text.back() == ',') return std::nullopt;
  if (values.size() != 4 && values.size() != 5) return std::nullopt;
  return values;
}

CLI::Option* addDistortionOption(CLI::App* command, std::vector<double>& target) {
  return command
      ->add_option_function<std::string>(
          "--distortion", [&target](const std::string& text) { target = *parseDistortion(text); },
          "Lens distortion k1,k2,p1,p2[,k3] (OpenCV order; e.g. -0.3,0,0,0 for a wide webcam); "
          "default: none")
      ->check(CLI::Validator(
          [](std::string& text) {
            return parseDistortion(text)
                       ? std::string()
                       : "expected k1,k2,p1,p2[,k3] (4 or 5 numbers), got " + text;
          },
          "K1,K2,P1,P2[,K3]"));
}

}  // namespace reftrack::app
