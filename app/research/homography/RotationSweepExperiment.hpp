#pragma once
// Pure-rotation sweep of homography mode (paper Fig. 15/16: 33 degree field of view, 100 image
// pairs per angle, no prior on the motion). For each angle the camera pans about its optical
// centre (alternately left and right) away from reference view A; each trial pairs a freshly
// noised reference with a freshly noised rotated frame and registers them cold (unguided), as
// the paper did. The true homography K R K^-1 gives exact annotation ground truth: the error is
// the mean deviation of a grid of reference annotations that lie inside the frame. A trial
// succeeds when it is tracked, that error is small and no annotation the frame does not see is
// drawn inside it (a fit right on a sliver of overlap may extrapolate wildly beyond it);
// tracked-but-wrong trials are counted apart.
// Rendering needs a current GL context (render::createHeadlessContext()).
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "app/simulator/CameraEffects.hpp"
#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

struct RotationSweepOptions {
  cv::Size size{320, 240};
  double fovDeg = 33.0;  // horizontal
  double maxAngleDeg = 33.0;
  double stepDeg = 3.0;
  int trials = 100;  // per angle
  double noiseSigma = 2.0;
  std::uint64_t seed = 1;
  // A tracked trial counts as a success only with an annotation error below this (pixels);
  // above it (or with no annotation inside the frame to check) it is "tracked but wrong".
  double successErrorPx = 2.0;
  // The tracker is given the camera's K, as a calibrated user's would be (enables the
  // rotation-only model, homography.rotation_model); false: the general homography alone.
  bool calibrated = true;
  // Lens distortion of the simulated camera (SimulationOptions::distortion; empty: none). The
  // reference and frame are undistorted (FrameUndistorter) before registration, where
  // K R K^-1 holds exactly; errors are in undistorted pixels.
  std::vector<double> distortion;
  TrackerParams params;
  // Webcam effects: photos in the scene and the still effects (defocus, vignetting, sensor
  // noise) on the reference and the frame of every trial; each trial is a cold pair of stills.
  CameraEffects effects;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct RotationStep {
  double angleDeg = 0.0;
  double overlap = 0.0;  // fraction of the frame that sees the reference (mean of both pans)
  int trials = 0;
  int successes = 0;               // tracked and annotation error < successErrorPx
  int rotationModelSuccesses = 0;  // successes registered with the rotation-only model
  int trackedButWrong = 0;         // tracked, but the error is larger (a wrong registration)
  double meanErrorPx = 0.0;        // annotation error over the successful trials (NaN if none)
  double medianErrorPx = 0.0;      // (NaN if none)
  double maxErrorPx = 0.0;
  double medianMs = 0.0;  // registration time per trial (the unguided frame; not the reference)
};

// One step per angle 0, step, 2 step, ... up to maxAngleDeg.
std::vector<RotationStep> runRotationSweep(const RotationSweepOptions& options);

}  // namespace reftrack::app
