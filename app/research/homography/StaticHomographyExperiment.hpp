#pragma once
// Static-camera experiment of homography mode (paper Sec. 7.3: 500/500 frames registered, mean
// deviation of the image centre < 1 px). The simulator renders reference view A once and then
// `frames` frames of the same view, each with fresh sensor noise; the tracker runs over them as
// over a video, and the image centre mapped by each H is compared with the centre itself.
// Rendering needs a current GL context (render::createHeadlessContext()).
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "app/simulator/CameraEffects.hpp"
#include "app/simulator/SimulationOptions.hpp"
#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

struct StaticExperimentOptions {
  cv::Size size{320, 240};
  int frames = 500;
  double fovDeg = 33.0;
  double noiseSigma = 2.0;  // grey levels
  std::uint64_t seed = 1;
  TrackerParams params;
  // Webcam effects on the frames (CameraEffectsPipeline at 30 fps; the reference gets its still
  // effects). A static camera: blur and rolling shutter change nothing.
  CameraEffects effects;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct StaticExperimentResult {
  int frames = 0;
  int registered = 0;
  std::vector<double> centreDeviationPx;  // per frame; NaN when the frame was not registered
  std::vector<double> milliseconds;       // tracker time per frame
  double meanDeviationPx = 0.0;           // over registered frames
  double maxDeviationPx = 0.0;
};

StaticExperimentResult runStaticExperiment(const StaticExperimentOptions& options);

// The simulator set for one still view (preset "static", one frame: reference view A), with the
// photos of `effects` in the scene; the homography experiments render their stills from it.
SimulationOptions staticViewSimulation(cv::Size size, double fovDeg, std::uint64_t seed,
                                       double noiseSigma, const CameraEffects& effects);

}  // namespace reftrack::app
