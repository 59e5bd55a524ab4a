#pragma once
// SimulatedSequence: everything a 6-DOF experiment needs from the simulator, made once and shared
// by every tracker run on it — the camera, the reference map prepared from the two marker-
// calibrated reference images (exactly as `reftrack prepare` does), the frames (grey) and the
// ground truth. Rendering needs a current GL context (render::createHeadlessContext()).
#include <filesystem>
#include <vector>

#include "app/simulator/SimulationOptions.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack::app {

struct SimulatedSequence {
  SimulationOptions options;
  PinholeCamera camera;
  Preparation preparation;      // map + report
  std::vector<cv::Mat> frames;  // CV_8UC1
  TumTrajectory groundTruth;    // camera in world, one entry per frame (timestamps k / fps)
};

// Renders the sequence (progress on stderr) and prepares the map from the marker.
SimulatedSequence simulateSequence(const SimulationOptions& options,
                                   const ReferencePreparerParams& preparation = {});

// The sequence of `options` from a folder under `cacheDir` named after every option that changes
// the frames, when an earlier call stored it there (map, grey PNG frames, ground truth; the
// preparation report is not kept); otherwise simulated as above and stored. Repeated experiments
// then skip the rendering. Throws reftrack::Error when a stored folder is inconsistent.
SimulatedSequence cachedSimulatedSequence(const SimulationOptions& options,
                                          const std::filesystem::path& cacheDir);

}  // namespace reftrack::app
