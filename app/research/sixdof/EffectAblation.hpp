#pragma once
// EffectAblation: the 6-DOF tracker (regularised PoseTracker on references A and B) on one
// simulated sequence rendered clean, with each webcam effect alone and with all of them (the
// `webcam` preset): tracked fraction, cube-vertex error (mean, p95) and lost frames, among them
// the sharp ones — frames whose cube vertices move less than 1 px during the webcam exposure
// (CameraEffects `blur` level), judged on the exact path. Same path, seed and map preparation in
// every row, so each row differs from the clean one by its effect only.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "app/simulator/SimulationOptions.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/estimation/MotionModel.hpp"

namespace reftrack::app {

struct EffectAblationRow {
  std::string effects;  // "none", an effect name or "webcam"
  int frames = 0, tracked = 0;
  double cubeMeanPx = 0.0, cubeP95Px = 0.0;  // NaN when nothing was tracked
  std::vector<int> lostFrames;
  std::vector<int> sharpLostFrames;  // lost with < 1 px of motion over the exposure
  std::string firstLostReason;       // "frame k: why", or ""
  double renderMsPerFrame = 0.0;     // wall time of the rendering, per frame
  double trackedPercent() const { return frames > 0 ? 100.0 * tracked / frames : 0.0; }
};

// One row per entry of `effectLists` (each as cameraEffectsFor accepts it; "none" = clean), on
// `base` (its own effects are replaced). `cacheDir` non-empty: rendered sequences are kept there.
std::vector<EffectAblationRow> runEffectAblation(const SimulationOptions& base,
                                                 const std::vector<std::string>& effectLists,
                                                 const TrackerParams& params,
                                                 const std::optional<ArMotionModel>& motion,
                                                 const std::filesystem::path& cacheDir = {});

// Per frame of the exact path of `s`: the largest image motion of the cube vertices during an
// exposure of `exposureFrames` frame periods (central difference of the ground truth).
struct SimulatedSequence;
std::vector<double> exposureMotionPx(const SimulatedSequence& s, double exposureFrames,
                                     double cubeSide = 0.1);

}  // namespace reftrack::app
