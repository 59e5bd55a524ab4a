#include "app/research/homography/HomographyBenchmark.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "app/cli/ProgressBar.hpp"
#include "app/research/baselines/OrbHomographyBaseline.hpp"
#include "app/research/homography/HomographyGroundTruth.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

namespace {

// Thread CPU time, not wall time: on a shared machine the wall clock counts other processes too.
double millisecondsSince(double cpuStartMs) { return threadCpuMs() - cpuStartMs; }

}  // namespace

void BenchmarkOptions::check() const {
  if (size.width < 64 || size.height < 48) throw Error("benchmark: size must be at least 64x48");
  if (frames < 1) throw Error("benchmark: frames must be at least 1");
  if (pathFrames != 0 && pathFrames < frames)
    throw Error("benchmark: pathFrames must be 0 or at least frames");
  if (!(fovDeg > 1.0 && fovDeg < 170.0)) throw Error("benchmark: fovDeg must be in (1, 170)");
  if (!(noiseSigma >= 0.0 && noiseSigma <= 100.0))
    throw Error("benchmark: noiseSigma must be in [0, 100]");
  params.check();
}

double finiteMedian(const std::vector<double>& values) {
  std::vector<double> v;
  for (double x : values)
    if (std::isfinite(x)) v.push_back(x);
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

BenchmarkResult runHomographyBenchmark(const BenchmarkOptions& options) {
  options.check();
  SimulationOptions sim;
  sim.preset = "rotate";
  sim.frames = options.pathFrames > 0 ? options.pathFrames : options.frames;
  sim.size = options.size;
  sim.fovDeg = options.fovDeg;
  sim.seed = options.seed;
  sim.noiseSigma = options.noiseSigma;
  SceneSimulator simulator(sim);
  const Eigen::Matrix3d K = simulator.camera().K();
  const RigidPose poseA = simulator.referencePoseA();
  // Frames are converted to grey once, outside the timed calls (both methods work on grey).
  const cv::Mat reference = toGray8(simulator.renderReference('A'));
  HomographyTracker tracker(reference, options.params);
  HomographyTracker calibratedTracker(reference, options.params, K);
  const OrbHomographyBaseline baseline(reference);

  BenchmarkResult out;
  out.size = options.size;
  out.frames = options.frames;
  out.tracker.name = "reftrack homography";
  out.calibratedTracker.name = "reftrack homography + K";
  out.baseline.name = "ORB+BF+findHomography";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ProgressBar progress(
      "benchmark " + std::to_string(options.size.width) + "x" + std::to_string(options.size.height),
      static_cast<std::size_t>(options.frames));
  for (int k = 0; k < options.frames; ++k) {
    const cv::Mat frame = toGray8(simulator.renderFrame(k));
    // Camera A -> frame k is a pure rotation (the preset turns about A's optical centre).
    const RigidPose aToK = simulator.framePose(k) * poseA.inverse();
    const cv::Matx33d trueH = rotationHomography(K, aToK.rotation());

    const auto runTracker = [&](HomographyTracker& t, BenchmarkSide& side) {
      const double t0 = threadCpuMs();
      const HomographyTrackResult r = t.track(frame);
      side.milliseconds.push_back(millisecondsSince(t0));
      side.cornerErrorPx.push_back(r.tracked ? frameCornerError(r.H, trueH, options.size) : nan);
      side.registered += r.tracked ? 1 : 0;
      for (size_t i = 0; i < r.stageMs.size(); ++i) {
        if (side.stageMs.size() <= i) side.stageMs.push_back({r.stageMs[i].first, {}});
        side.stageMs[i].second.push_back(r.stageMs[i].second);
      }
      if (!r.tracked) side.failures.push_back("frame " + std::to_string(k) + ": " + r.failure);
    };
    // Alternately first, so neither gains from the other having warmed the caches.
    if (k % 2 == 0) {
      runTracker(tracker, out.tracker);
      runTracker(calibratedTracker, out.calibratedTracker);
    } else {
      runTracker(calibratedTracker, out.calibratedTracker);
      runTracker(tracker, out.tracker);
    }

    const double t0 = threadCpuMs();
    const OrbHomographyResult b = baseline.track(frame);
    out.baseline.milliseconds.push_back(millisecondsSince(t0));
    out.baseline.cornerErrorPx.push_back(b.tracked ? frameCornerError(b.H, trueH, options.size)
                                                   : nan);
    out.baseline.registered += b.tracked ? 1 : 0;
    if (!b.tracked)
      out.baseline.failures.push_back("frame " + std::to_string(k) + ": " +
                                      std::to_string(b.inliers) + " inliers of " +
                                      std::to_string(b.matches) + " matches");
    progress.advance();
  }
  progress.finish();
  return out;
}

}  // namespace reftrack::app
