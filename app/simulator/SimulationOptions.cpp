#include "app/simulator/SimulationOptions.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include "engine/core/Error.hpp"

namespace reftrack::app {

const std::vector<std::string>& simulationPresets() {
  static const std::vector<std::string> names = {"handheld", "orbit",   "rotate",
                                                 "static",   "forward", "walkaround"};
  return names;
}

std::optional<cv::Size> parseImageSize(const std::string& text) {
  static const std::regex form("([1-9][0-9]{0,4})x([1-9][0-9]{0,4})");
  std::smatch m;
  if (!std::regex_match(text, m, form)) return std::nullopt;
  return cv::Size(std::stoi(m[1].str()), std::stoi(m[2].str()));
}

int SimulationOptions::referenceCount() const {
  if (references != 0) return references;
  return preset == "walkaround" ? 6 : 2;
}

void SimulationOptions::check() const {
  const auto& presets = simulationPresets();
  if (std::find(presets.begin(), presets.end(), preset) == presets.end()) {
    std::string known;
    for (const auto& p : presets) known += (known.empty() ? "" : ", ") + p;
    throw Error("simulation preset '" + preset + "' is unknown (known: " + known + ")");
  }
  if (frames < 1)
    throw Error("simulation frames must be at least 1, got " + std::to_string(frames));
  // The smallest size still shows the marker; the largest keeps the 3x supersampled render
  // within common GL limits (16384).
  if (size.width < 32 || size.height < 32 || size.width > 4096 || size.height > 4096)
    throw Error("simulation size must be between 32x32 and 4096x4096, got " +
                std::to_string(size.width) + "x" + std::to_string(size.height));
  if (!(std::isfinite(noiseSigma) && noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("simulation noiseSigma must be in [0, 100] grey levels");
  if (!(std::isfinite(fovDeg) && fovDeg >= 10.0 && fovDeg <= 150.0))
    throw Error("simulation fovDeg must be in [10, 150] degrees");
  if (!(std::isfinite(fps) && fps > 0.0 && fps <= 1000.0))
    throw Error("simulation fps must be in (0, 1000]");
  effects.check();
  if (!distortion.empty() && distortion.size() != 4 && distortion.size() != 5)
    throw Error("simulation distortion must be k1,k2,p1,p2[,k3] (4 or 5 values), got " +
                std::to_string(distortion.size()));
  for (double d : distortion)
    if (!(std::isfinite(d) && std::abs(d) <= 10.0))
      throw Error("simulation distortion coefficients must be finite and within [-10, 10]");
  if (!(referenceBaseline >= 0.0 && referenceBaseline <= 1.0))
    throw Error(
        "simulation referenceBaseline must be 0 (the scene's default) or in (0, 1] m, got " +
        std::to_string(referenceBaseline));
  if (references != 0 && (references < 2 || references > kMaxReferences))
    throw Error("simulation references must be 0 (the preset's default) or 2.." +
                std::to_string(kMaxReferences) + ", got " + std::to_string(references));
}

}  // namespace reftrack::app
