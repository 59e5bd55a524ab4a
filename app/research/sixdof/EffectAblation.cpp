#include "app/research/sixdof/EffectAblation.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <set>

#include "app/cli/ProgressBar.hpp"
#include "app/research/sixdof/SimulatedSequence.hpp"
#include "app/research/sixdof/SixDofRuns.hpp"
#include "app/simulator/CameraEffectsPipeline.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"

namespace reftrack::app {

namespace {

// Effects that change neither the scene nor need renders between frames: their sequence is made
// from the clean renders (one per frame, made once for every such row) exactly as
// SceneSimulator::renderFrame would make it, which saves a render per frame and row.
bool photometricOnly(const SimulationOptions& o) {
  return !o.blur && !o.effects.photos && !o.effects.motionDependent();
}

std::vector<cv::Mat> cleanRenders(const SimulationOptions& base) {
  SimulationOptions o = base;
  o.effects = {};
  SceneSimulator sim(o);
  std::vector<cv::Mat> renders;
  ProgressBar progress("render clean " + o.preset, static_cast<std::size_t>(o.frames));
  for (int k = 0; k < o.frames; ++k) {
    renders.push_back(sim.renderView(sim.framePose(k), 0, 0.0));
    progress.advance();
  }
  progress.finish();
  return renders;
}

SimulatedSequence sequenceFromRenders(const SimulationOptions& o,
                                      const std::vector<cv::Mat>& renders) {
  SceneSimulator sim(o);  // the references, with their still effects and noise seeds
  SimulatedSequence s;
  s.options = o;
  s.camera = sim.camera();
  s.preparation = ReferencePreparer(s.camera).prepare(
      {sim.renderReference('A'), "simulated reference A"},
      {sim.renderReference('B'), "simulated reference B"}, sim.marker());
  CameraEffectsPipeline camera(
      o.effects, CameraSetup{o.size, o.fps, o.frames, o.seed, o.noiseSigma},
      [&](double t) { return renders[static_cast<std::size_t>(std::lround(t))]; });
  for (int k = 0; k < o.frames; ++k) {
    cv::Mat gray;
    cv::cvtColor(camera.frame(k), gray, cv::COLOR_BGR2GRAY);
    s.frames.push_back(gray);
    s.groundTruth.poses.push_back({k / o.fps, sim.framePose(k)});
  }
  return s;
}

}  // namespace

std::vector<double> exposureMotionPx(const SimulatedSequence& s, double exposureFrames,
                                     double cubeSide) {
  const std::vector<Eigen::Vector3d> cube = cubeVertices(cubeSide);
  const std::size_t n = s.groundTruth.poses.size();
  std::vector<double> motion(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t a = k > 0 ? k - 1 : k, b = k + 1 < n ? k + 1 : k;
    if (a == b) continue;
    const RigidPose& pa = s.groundTruth.poses[a].worldToCamera;
    const RigidPose& pb = s.groundTruth.poses[b].worldToCamera;
    double largest = 0.0;
    for (const Eigen::Vector3d& X : cube)
      largest = std::max(largest, (s.camera.project(pb, X) - s.camera.project(pa, X)).norm());
    motion[k] = largest / static_cast<double>(b - a) * exposureFrames;
  }
  return motion;
}

std::vector<EffectAblationRow> runEffectAblation(const SimulationOptions& base,
                                                 const std::vector<std::string>& effectLists,
                                                 const TrackerParams& params,
                                                 const std::optional<ArMotionModel>& motion,
                                                 const std::filesystem::path& cacheDir) {
  TrackerParams regularised = params;
  regularised.pose.estimator = PoseEstimatorKind::Regularised;
  const double webcamExposureFrames =
      cameraEffectsFor("blur", base.size).exposureMs * 1e-3 * base.fps;
  std::vector<EffectAblationRow> rows;
  std::vector<cv::Mat> renders;  // clean, made at the first photometric row
  for (const std::string& list : effectLists) {
    SimulationOptions o = base;
    o.effects = cameraEffectsFor(list, o.size);
    const auto t0 = std::chrono::steady_clock::now();
    SimulatedSequence s;
    if (photometricOnly(o)) {
      if (renders.empty()) renders = cleanRenders(base);
      s = sequenceFromRenders(o, renders);
    } else {
      s = cacheDir.empty() ? simulateSequence(o) : cachedSimulatedSequence(o, cacheDir);
    }
    EffectAblationRow row;
    row.effects = list;
    row.frames = static_cast<int>(s.frames.size());
    row.renderMsPerFrame =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count() /
        std::max(1, row.frames);
    const TrackerRun run = runPoseTracker(s, regularised, list, motion);
    row.tracked = static_cast<int>(run.estimate.poses.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    row.cubeMeanPx = run.evaluation.cubeErrorPx ? run.evaluation.cubeErrorPx->mean : nan;
    row.cubeP95Px = run.evaluation.cubeErrorPx ? run.evaluation.cubeErrorPx->p95 : nan;
    std::set<double> trackedTimes;
    for (const StampedPose& p : run.estimate.poses) trackedTimes.insert(p.timestamp);
    const std::vector<double> blur = exposureMotionPx(s, webcamExposureFrames);
    for (int k = 0; k < row.frames; ++k) {
      if (trackedTimes.count(s.groundTruth.poses[static_cast<std::size_t>(k)].timestamp)) continue;
      row.lostFrames.push_back(k);
      if (blur[static_cast<std::size_t>(k)] < 1.0) row.sharpLostFrames.push_back(k);
    }
    if (!run.lostReasons.empty()) row.firstLostReason = run.lostReasons.front();
    rows.push_back(row);
  }
  return rows;
}

}  // namespace reftrack::app
