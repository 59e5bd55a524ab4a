#include "app/research/relocalisation/RelocalisationExperiment.hpp"

#include <chrono>
#include <limits>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "app/cli/ProgressBar.hpp"
#include "app/research/baselines/OrbPnpColdStart.hpp"
#include "app/research/sixdof/SixDofRuns.hpp"
#include "app/simulator/SensorNoise.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack::app {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

cv::Mat grey(const cv::Mat& bgr) {
  cv::Mat g;
  cv::cvtColor(bgr, g, cv::COLOR_BGR2GRAY);
  return g;
}

// Noise streams of the trials, apart from the simulator's frames and references.
constexpr std::uint64_t kColdStartStream = 0x434F4C44ull, kKidnapStream = 0x4B49444Eull;

}  // namespace

void RelocalisationExperimentOptions::check() const {
  if (coldStarts < 0) throw Error("relocalisation experiment: coldStarts must be >= 0");
  if (kidnaps < 0) throw Error("relocalisation experiment: kidnaps must be >= 0");
  if (blackFrames < 0) throw Error("relocalisation experiment: blackFrames must be >= 0");
  if (!(successPx > 0.0 && wrongPx >= successPx))
    throw Error("relocalisation experiment: successPx must be > 0 and <= wrongPx");
  if (!(cubeSide > 0.0)) throw Error("relocalisation experiment: cubeSide must be positive");
  views.check();
}

FrameTracker multiReferenceFrameTracker(const MultiReferenceMap& map, const TrackerParams& params) {
  auto tracker = std::make_shared<MultiReferenceTracker>(map, params);
  return [tracker](const cv::Mat& frame) {
    const MultiReferenceResult r = tracker->process(frame);
    FrameOutcome out(r.tracking.worldToCamera);
    out.message = r.tracking.message;
    if (r.relocalisation.attempted) {
      out.message += " [relocaliser: " + r.relocalisation.message + "]";
      out.relocaliseMs = r.relocalisation.locateMs;
      out.relocaliseCpuMs = r.relocalisation.locateCpuMs;
    }
    return out;
  };
}

double poseCubeErrorPx(const PinholeCamera& camera, const RigidPose& truth,
                       const RigidPose& estimate, double cubeSide) {
  TumTrajectory gt, est;
  gt.poses = {{0.0, truth}};
  est.poses = {{0.0, estimate}};
  EvaluationParams params;
  params.cubeSide = cubeSide;
  const TrajectoryEvaluation e = evaluateTrajectory(gt, est, params, &camera);
  // No vertex in front of both cameras: as wrong as a pose gets.
  if (e.frames.empty() || !e.frames[0].cubeErrorPx) return std::numeric_limits<double>::infinity();
  return *e.frames[0].cubeErrorPx;
}

RateSummary RelocalisationExperimentResult::coldStart() const {
  RateSummary r;
  r.trials = static_cast<int>(coldStarts.size());
  for (const ColdStartTrial& t : coldStarts) {
    if (!t.posed) continue;
    if (t.cubeErrorPx <= successPx) ++r.good;
    if (t.cubeErrorPx > wrongPx) ++r.wrong;
  }
  return r;
}

RateSummary RelocalisationExperimentResult::coldStartBaseline() const {
  RateSummary r;
  for (const ColdStartTrial& t : coldStarts) {
    if (t.baselineMs <= 0.0) continue;  // baseline not run
    ++r.trials;
    if (!t.baselinePosed) continue;
    if (t.baselineErrorPx <= successPx) ++r.good;
    if (t.baselineErrorPx > wrongPx) ++r.wrong;
  }
  return r;
}

RateSummary RelocalisationExperimentResult::kidnap() const {
  RateSummary r;
  r.trials = static_cast<int>(kidnaps.size());
  for (const KidnapTrial& t : kidnaps) {
    if (t.recoveredOnFrame > 0) ++r.good;
    r.wrong += t.wrongPoses;
  }
  return r;
}

double RelocalisationExperimentResult::medianColdStartMs() const {
  std::vector<double> ms;
  for (const ColdStartTrial& t : coldStarts) ms.push_back(t.ms);
  return median(ms);
}

double RelocalisationExperimentResult::medianBaselineMs() const {
  std::vector<double> ms;
  for (const ColdStartTrial& t : coldStarts)
    if (t.baselineMs > 0.0) ms.push_back(t.baselineMs);
  return median(ms);
}

double RelocalisationExperimentResult::medianBaselineCpuMs() const {
  std::vector<double> ms;
  for (const ColdStartTrial& t : coldStarts)
    if (t.baselineMs > 0.0) ms.push_back(t.baselineCpuMs);
  return median(ms);
}

double RelocalisationExperimentResult::medianColdStartCpuMs() const {
  std::vector<double> ms;
  for (const ColdStartTrial& t : coldStarts) ms.push_back(t.cpuMs);
  return median(ms);
}

double RelocalisationExperimentResult::medianRelocaliseMs() const {
  std::vector<double> ms;
  for (const ColdStartTrial& t : coldStarts)
    if (t.relocaliseMs >= 0.0) ms.push_back(t.relocaliseMs);
  return median(ms);
}

double RelocalisationExperimentResult::medianRelocaliseCpuMs() const {
  std::vector<double> ms;
  for (const ColdStartTrial& t : coldStarts)
    if (t.relocaliseCpuMs >= 0.0) ms.push_back(t.relocaliseCpuMs);
  return median(ms);
}

TrackedFrameTiming compareTrackedFrameMs(const std::vector<cv::Mat>& frames,
                                         const FrameTracker& first, const FrameTracker& second) {
  TrackedFrameTiming timing;
  const auto timed = [](const FrameTracker& tracker, const cv::Mat& frame, std::vector<double>& ms,
                        std::vector<double>& cpuMs) {
    const Clock::time_point t0 = Clock::now();
    const double cpu0 = threadCpuMs();
    const bool posed = tracker(frame).pose.has_value();
    const double cpu = threadCpuMs() - cpu0;
    const double elapsed = msSince(t0);
    if (!posed) return;
    ms.push_back(elapsed);
    cpuMs.push_back(cpu);
  };
  for (std::size_t k = 0; k < frames.size(); ++k) {
    if (k % 2 == 0) {
      timed(first, frames[k], timing.msFirst, timing.cpuMsFirst);
      timed(second, frames[k], timing.msSecond, timing.cpuMsSecond);
    } else {
      timed(second, frames[k], timing.msSecond, timing.cpuMsSecond);
      timed(first, frames[k], timing.msFirst, timing.cpuMsFirst);
    }
  }
  return timing;
}

RelocalisationExperimentResult runRelocalisationExperiment(
    SceneSimulator& sim, const MultiReferenceMap& map, const TrackerFactory& makeTracker,
    const RelocalisationExperimentOptions& o) {
  o.check();
  RelocalisationExperimentResult result;
  result.successPx = o.successPx;
  result.wrongPx = o.wrongPx;
  const double noise = sim.options().noiseSigma;
  const PinholeCamera& camera = sim.camera();
  std::optional<OrbPnpColdStart> baseline;
  if (o.baseline && o.coldStarts > 0) baseline.emplace(map);

  // (a) cold start.
  RandomViewSampler coldViews(sim.referencePoses(), sim.lookedAt(),
                              mixSeed(o.seed, kColdStartStream), o.views);
  ProgressBar coldProgress("cold start", static_cast<std::size_t>(o.coldStarts));
  for (int i = 0; i < o.coldStarts; ++i) {
    ColdStartTrial t;
    t.view = coldViews.next();
    const cv::Mat frame = grey(
        sim.renderView(t.view.worldToCamera, mixSeed(mixSeed(o.seed, kColdStartStream), i), noise));
    FrameTracker tracker = makeTracker();
    const Clock::time_point t0 = Clock::now();
    const double cpu0 = threadCpuMs();
    const FrameOutcome outcome = tracker(frame);
    t.cpuMs = threadCpuMs() - cpu0;
    t.ms = msSince(t0);
    t.relocaliseMs = outcome.relocaliseMs;
    t.relocaliseCpuMs = outcome.relocaliseCpuMs;
    t.trackerMessage = outcome.message;
    const std::optional<RigidPose>& pose = outcome.pose;
    t.message = "no pose";
    if (pose) {
      t.posed = true;
      t.cubeErrorPx = poseCubeErrorPx(camera, t.view.worldToCamera, *pose, o.cubeSide);
      t.message = t.cubeErrorPx <= o.successPx ? "good"
                  : t.cubeErrorPx > o.wrongPx  ? "wrong"
                                               : "coarse";
    }
    if (baseline) {
      const Clock::time_point b0 = Clock::now();
      const double cpu1 = threadCpuMs();
      const OrbPnpColdStartResult b = baseline->locate(frame);
      t.baselineCpuMs = threadCpuMs() - cpu1;
      t.baselineMs = msSince(b0);
      if (b.worldToCamera) {
        t.baselinePosed = true;
        t.baselineErrorPx =
            poseCubeErrorPx(camera, t.view.worldToCamera, *b.worldToCamera, o.cubeSide);
      }
    }
    result.coldStarts.push_back(t);
    coldProgress.advance();
  }
  coldProgress.finish();

  // (b) kidnapped camera: one tracker throughout; each trial starts where the last one ended.
  if (o.kidnaps > 0) {
    RandomViewSampler kidnapViews(sim.referencePoses(), sim.lookedAt(),
                                  mixSeed(o.seed, kKidnapStream), o.views);
    FrameTracker tracker = makeTracker();
    const std::uint64_t noiseSeed = mixSeed(o.seed, kKidnapStream);
    // Start tracking at reference view 0 (a view the tracker always knows).
    tracker(grey(sim.renderView(sim.referencePoses()[0], mixSeed(noiseSeed, 1u << 30), noise)));
    const cv::Mat black = cv::Mat::zeros(camera.imageSize(), CV_8UC1);
    ProgressBar progress("kidnapped", static_cast<std::size_t>(o.kidnaps));
    for (int i = 0; i < o.kidnaps; ++i) {
      KidnapTrial t;
      t.view = kidnapViews.next();
      for (int k = 0; k < o.blackFrames; ++k)
        if (tracker(black).pose) ++t.posesOnBlack;
      t.wrongPoses += t.posesOnBlack;
      for (int clear = 1; clear <= 2; ++clear) {
        const cv::Mat frame = grey(
            sim.renderView(t.view.worldToCamera,
                           mixSeed(noiseSeed, static_cast<std::uint64_t>(2 * i + clear)), noise));
        const FrameOutcome outcome = tracker(frame);
        t.trackerMessage += (clear > 1 ? "; " : "") + outcome.message;
        const std::optional<RigidPose>& pose = outcome.pose;
        if (!pose) continue;
        const double e = poseCubeErrorPx(camera, t.view.worldToCamera, *pose, o.cubeSide);
        if (e > o.wrongPx) ++t.wrongPoses;
        if (t.recoveredOnFrame == 0 && e <= o.successPx) {
          t.recoveredOnFrame = clear;
          t.cubeErrorPx = e;
        }
      }
      result.kidnaps.push_back(t);
      progress.advance();
    }
    progress.finish();
  }
  return result;
}

}  // namespace reftrack::app
