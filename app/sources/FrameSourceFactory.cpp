#include "app/sources/FrameSourceFactory.hpp"

#include <algorithm>
#include <charconv>
#include <filesystem>

#include "app/sources/CameraSource.hpp"
#include "app/sources/EurocSequenceSource.hpp"
#include "app/sources/ImageFolderSource.hpp"
#include "app/sources/SimulatorSource.hpp"
#include "app/sources/TumSequenceSource.hpp"
#include "app/sources/VideoFileSource.hpp"
#include "engine/core/Error.hpp"
#include "engine/dataset/DatasetSpec.hpp"

namespace reftrack::app {

namespace {

bool startsWith(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

bool isSimulatorInput(const std::string& input) { return startsWith(input, "sim:"); }

std::unique_ptr<FrameSource> openFrameSource(const std::string& input,
                                             const FrameSourceOptions& options) {
  if (input.empty()) throw Error("--input is empty");
  if (startsWith(input, "camera:")) {
    const std::string digits = input.substr(7);
    int index = -1;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), index);
    if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || index < 0)
      throw Error("input '" + input + "': expected camera:N with N a camera index (0, 1, ...)");
    return std::make_unique<CameraSource>(index);
  }
  if (isSimulatorInput(input)) {
    const std::string preset = input.substr(4);
    const auto& presets = simulationPresets();
    if (std::find(presets.begin(), presets.end(), preset) == presets.end()) {
      std::string names;
      for (const std::string& p : presets) names += (names.empty() ? "" : ", ") + p;
      throw Error("input '" + input + "': unknown simulator preset (known: " + names + ")");
    }
    SimulationOptions sim;
    sim.preset = preset;
    sim.frames = options.simFrames;
    sim.size = options.simSize;
    sim.seed = options.simSeed;
    sim.fps = options.imageFps;
    return std::make_unique<SimulatorSource>(sim);
  }
  if (const std::optional<DatasetSpec> dataset = parseDatasetSpec(input)) {
    if (dataset->layout == DatasetLayout::Tum)
      return std::make_unique<TumSequenceSource>(dataset->dir);
    return std::make_unique<EurocSequenceSource>(dataset->dir);
  }
  if (input.find_first_of("*?[") != std::string::npos)
    return std::make_unique<ImageFolderSource>(input, options.imageFps, options.anyImageSizes);
  if (std::filesystem::is_directory(input))
    return std::make_unique<ImageFolderSource>(input, options.imageFps, options.anyImageSizes);
  return std::make_unique<VideoFileSource>(input);
}

}  // namespace reftrack::app
