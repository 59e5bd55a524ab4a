#pragma once
// Relocalisation benchmark (issue 13): the Relocaliser and the plain ORB + solvePnPRansac baseline
// (OrbPnpColdStart) on the same frames against the same map, alternating per frame so both see
// the same machine load: per-attempt milliseconds, success and wrong-pose counts, pose errors
// against ground truth. The caller sets the thread count (cv::setNumThreads(1) for the figures).
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/RelocalisationParams.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

struct RelocalisationBenchmarkSide {
  std::string name;
  int attempts = 0;
  int found = 0;                        // a pose returned (on frames with ground truth)
  int wrong = 0;                        // a pose off by more than the wrong-pose bounds
  std::vector<double> milliseconds;     // every attempt, wall
  std::vector<double> cpuMilliseconds;  // every attempt, the thread's CPU time
  std::vector<double> centreErrorMm, rotationErrorDeg;  // each pose returned on a frame with truth
};

struct RelocalisationBenchmarkResult {
  RelocalisationBenchmarkSide relocaliser, baseline;
  double medianMsRatio = 0.0;     // relocaliser median ms / baseline median ms (wall)
  double medianCpuMsRatio = 0.0;  // the same with thread CPU time
};

struct RelocalisationBenchmarkOptions {
  RelocalisationParams params;  // of the Relocaliser (the map's layer must be of its kind)
  double wrongCentreMm = 50.0;  // a pose farther off than either bound is counted wrong
  double wrongRotationDeg = 2.0;
};

// frames: grey or BGR at the map's size; truth: world->camera per frame, nullopt where unknown
// (those frames are timed but not scored). The baseline needs an ORB keypoint layer: when the
// map's is another kind, an ORB layer is built on a copy of the map (not timed).
RelocalisationBenchmarkResult runRelocalisationBenchmark(
    const MultiReferenceMap& map, const std::vector<cv::Mat>& frames,
    const std::vector<std::optional<RigidPose>>& truth,
    const RelocalisationBenchmarkOptions& options = {});

// One line per side: found/attempts, wrong, median and p90 ms (wall), median CPU ms, median
// centre and rotation errors; then the ratios of the medians.
void printRelocalisationBenchmark(const RelocalisationBenchmarkResult& result, std::FILE* out);

}  // namespace reftrack::app
