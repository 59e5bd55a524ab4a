#pragma once
// Benchmark of homography mode against the baseline users reach for today (OrbHomographyBaseline)
// on the very same frames: a simulated pure-rotation sequence (preset "rotate": the camera pans
// +-40 degrees about reference view A's optical centre), so each frame's true homography
// K R K^-1 is exact. Both register every frame to reference A; per frame the time of the call
// (thread CPU) and the registration error at the frame's corners are recorded. Single thread: call
// cv::setNumThreads(1) first for the paper's one-core figures. Needs a current GL context.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "engine/config/TrackerParams.hpp"

namespace reftrack::app {

struct BenchmarkOptions {
  cv::Size size{640, 480};
  int frames = 150;    // frames registered: the first `frames` of the path
  int pathFrames = 0;  // length of the pan (one full +-40 degree cycle); 0 = frames
  double fovDeg = 60.0;
  double noiseSigma = 2.0;
  std::uint64_t seed = 1;
  TrackerParams params;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct BenchmarkSide {
  std::string name;
  std::vector<double> milliseconds;   // per frame, thread CPU time of the call
  std::vector<double> cornerErrorPx;  // per frame; NaN when the frame was not registered
  int registered = 0;
  std::vector<std::string> failures;  // "frame k: reason" of unregistered frames
  // Per named stage (in the tracker's order), milliseconds per frame (the tracker only).
  std::vector<std::pair<std::string, std::vector<double>>> stageMs;
};

struct BenchmarkResult {
  cv::Size size;
  int frames = 0;
  BenchmarkSide tracker, baseline;
  // The tracker given the camera's K (rotation-only model enabled), on the same frames.
  BenchmarkSide calibratedTracker;
};

BenchmarkResult runHomographyBenchmark(const BenchmarkOptions& options);

// Median of the finite values; NaN when there are none.
double finiteMedian(const std::vector<double>& values);

}  // namespace reftrack::app
