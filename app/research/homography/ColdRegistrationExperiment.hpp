#pragma once
// Cold registration of a simulated planar target from any view: a textured 0.4 x 0.3 m card in
// front of an unrelated textured wall is the stored reference, seen head-on and filling the
// frame. Each trial renders the card from a random view — out-of-plane rotation (tilt) in
// [0, maxTiltDeg] about a random in-plane axis, scale (reference distance / distance) log-uniform
// in [minScale, maxScale], any in-plane rotation, the look-at point a few cm off the card centre —
// and registers it as a first frame (HomographyTracker::reset() before each). The card's plane
// gives the exact homography K [r1 r2 t] of each view. Error: mean registration error at the
// frame's four corners (frameCornerError). Needs a current GL context.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

struct ColdRegistrationOptions {
  cv::Size size{640, 480};
  double fovDeg = 60.0;  // horizontal
  int trials = 200;
  double maxTiltDeg = 50.0;
  double minScale = 0.5, maxScale = 2.0;
  double noiseSigma = 2.0;
  std::uint64_t seed = 1;
  double successErrorPx = 1.0;  // a tracked trial with a larger corner error is "wrong"
  TrackerParams params;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct ColdTrial {
  double tiltDeg = 0.0, scale = 1.0, rollDeg = 0.0;
  bool tracked = false;
  bool keypointGuided = false;  // registered through the keypoint layer
  double cornerErrorPx = 0.0;   // NaN when not tracked
  double milliseconds = 0.0;
  std::string failure;  // the tracker's reason when not tracked
};

// Trials in order (deterministic in options.seed).
std::vector<ColdTrial> runColdRegistration(const ColdRegistrationOptions& options);

struct ColdBucket {
  std::string label;
  int trials = 0, successes = 0, wrong = 0;    // wrong: tracked with error > successErrorPx
  double meanErrorPx = 0.0, maxErrorPx = 0.0;  // over the successes (NaN if none)
  double medianMs = 0.0;
};

// Trials grouped by tilt (edges in degrees) or by scale (edges), plus one "all" bucket last.
std::vector<ColdBucket> bucketByTilt(const std::vector<ColdTrial>& trials,
                                     const std::vector<double>& edges, double successErrorPx);
std::vector<ColdBucket> bucketByScale(const std::vector<ColdTrial>& trials,
                                      const std::vector<double>& edges, double successErrorPx);

}  // namespace reftrack::app
