#include "app/research/sixdof/SixDofRuns.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "app/cli/ProgressBar.hpp"
#include "app/research/baselines/OrbPnpKalmanTracker.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack::app {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

namespace {

// SD over time of each cube vertex's projected position (x and y pooled), averaged over the
// vertices: the jitter a viewer sees on a static camera.
double projectedJitter(const SimulatedSequence& s, const TumTrajectory& estimate, double cubeSide) {
  const std::vector<Eigen::Vector3d> cube = cubeVertices(cubeSide);
  if (estimate.poses.size() < 3) return 0.0;
  double total = 0.0;
  for (const Eigen::Vector3d& X : cube) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    std::vector<Eigen::Vector2d> p;
    for (const StampedPose& e : estimate.poses) p.push_back(s.camera.project(e.worldToCamera, X));
    for (const Eigen::Vector2d& q : p) mean += q;
    mean /= static_cast<double>(p.size());
    double ss = 0.0;
    for (const Eigen::Vector2d& q : p) ss += (q - mean).squaredNorm();
    total += std::sqrt(ss / (2.0 * static_cast<double>(p.size() - 1)));
  }
  return total / static_cast<double>(cube.size());
}

void evaluate(const SimulatedSequence& s, TrackerRun& run, double cubeSide) {
  EvaluationParams params;
  params.cubeSide = cubeSide;
  params.maxTimeDifference = 0.25 / s.options.fps;
  if (!run.estimate.poses.empty())
    run.evaluation = evaluateTrajectory(s.groundTruth, run.estimate, params, &s.camera);
  std::vector<double> cube;
  for (const FrameEvaluation& f : run.evaluation.frames)
    if (f.cubeErrorPx) cube.push_back(*f.cubeErrorPx);
  const std::size_t n = std::min<std::size_t>(100, cube.size() / 2);
  if (n > 0) {
    double first = 0, last = 0;
    for (std::size_t i = 0; i < n; ++i) {
      first += cube[i];
      last += cube[cube.size() - 1 - i];
    }
    run.firstHundredMeanPx = first / static_cast<double>(n);
    run.lastHundredMeanPx = last / static_cast<double>(n);
  }
  run.staticJitterPx = projectedJitter(s, run.estimate, cubeSide);
}

using Clock = std::chrono::steady_clock;

}  // namespace

TrackerRun runPoseTracker(const SimulatedSequence& s, const TrackerParams& params,
                          const std::string& name, const std::optional<ArMotionModel>& motion,
                          double cubeSide) {
  TrackerRun run;
  run.name = name;
  PoseTracker tracker(s.preparation.map, params);
  if (motion) tracker.setMotionModel(*motion);
  ProgressBar progress("track " + name, s.frames.size());
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const Clock::time_point t0 = Clock::now();
    const double cpu0 = threadCpuMs();
    const PoseTrackingResult r = tracker.process(s.frames[k]);
    run.frameMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    run.frameCpuMs.push_back(threadCpuMs() - cpu0);
    for (const StageTiming& st : r.timings) run.stageMs[st.stage].push_back(st.ms);
    if (r.worldToCamera) {
      run.estimate.poses.push_back({s.groundTruth.poses[k].timestamp, *r.worldToCamera});
      run.motion.push_back(r.T_Ak->toVector6());
    } else {
      ++run.lostFrames;
      run.lostReasons.push_back("frame " + std::to_string(k) + ": " + r.message);
      run.motion.push_back(std::nullopt);
    }
    progress.advance();
  }
  progress.finish();
  evaluate(s, run, cubeSide);
  return run;
}

TrackerRun runMultiReferenceTracker(const SimulatedSequence& s, const TrackerParams& params,
                                    const std::string& name,
                                    const std::optional<ArMotionModel>& motion, double cubeSide) {
  if (!s.references) throw Error("the simulated sequence was prepared without its N-reference map");
  TrackerRun run;
  run.name = name;
  MultiReferenceTracker tracker(*s.references, params);
  if (motion) tracker.setMotionModel(*motion);
  ProgressBar progress("track " + name, s.frames.size());
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const Clock::time_point t0 = Clock::now();
    const double cpu0 = threadCpuMs();
    const MultiReferenceResult m = tracker.process(s.frames[k]);
    run.frameMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    run.frameCpuMs.push_back(threadCpuMs() - cpu0);
    const PoseTrackingResult& r = m.tracking;
    for (const StageTiming& st : r.timings) run.stageMs[st.stage].push_back(st.ms);
    run.motion.push_back(std::nullopt);  // x_Ak is relative to whichever pair is in use
    if (r.worldToCamera) {
      run.estimate.poses.push_back({s.groundTruth.poses[k].timestamp, *r.worldToCamera});
      ++run.pairUse[std::to_string(m.referenceA) + "-" + std::to_string(m.referenceB)];
    } else {
      ++run.lostFrames;
      run.lostReasons.push_back("frame " + std::to_string(k) + ": " + r.message);
    }
    progress.advance();
  }
  progress.finish();
  evaluate(s, run, cubeSide);
  return run;
}

TrackerRun runOrbBaseline(const SimulatedSequence& s, double cubeSide) {
  TrackerRun run;
  run.name = "ORB+PnP+Kalman";
  OrbPnpKalmanParams params;
  params.dt = 1.0 / s.options.fps;
  OrbPnpKalmanTracker baseline(s.preparation.map, params);
  ProgressBar progress("track baseline", s.frames.size());
  for (std::size_t k = 0; k < s.frames.size(); ++k) {
    const Clock::time_point t0 = Clock::now();
    const double cpu0 = threadCpuMs();
    const std::optional<RigidPose> pose = baseline.process(s.frames[k]);
    run.frameMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    run.frameCpuMs.push_back(threadCpuMs() - cpu0);
    if (pose)
      run.estimate.poses.push_back({s.groundTruth.poses[k].timestamp, *pose});
    else
      ++run.lostFrames;
    run.motion.push_back(std::nullopt);
    progress.advance();
  }
  progress.finish();
  evaluate(s, run, cubeSide);
  return run;
}

}  // namespace reftrack::app
