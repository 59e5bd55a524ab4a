#pragma once
// The relocalisation experiment of issue 13, on the simulator's exact poses (one thread):
//  (a) cold start: random single views in the mapped volume (RandomViewSampler), each the first
//      frame of a fresh MultiReferenceTracker: posed within successPx (cube-vertex error), and
//      wrong poses (error above wrongPx); the ORB + solvePnPRansac baseline on the same views;
//  (b) kidnapped camera: one tracker, tracking a view; then blackFrames black frames and the
//      camera at the next random view (shown twice, fresh noise): recovered on the first or
//      second clear frame, and wrong poses on any frame;
//  (c) speed: per-frame ms of the tracker over the same sequence with a map of many references
//      and a map of two (tracked frames only), and ms of the cold-start attempts of (a).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/simulator/RandomViewSampler.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

struct RelocalisationExperimentOptions {
  int coldStarts = 200;
  int kidnaps = 100;
  int blackFrames = 30;
  double successPx = 1.5;  // cube-vertex error of a good pose
  double wrongPx = 5.0;    // a pose worse than this is wrong
  double cubeSide = 0.1;
  std::uint64_t seed = 1;  // views and their sensor noise
  RandomViewParams views;
  bool baseline = true;  // the ORB + solvePnPRansac cold start on the views of (a)
  void check() const;    // throws reftrack::Error naming the bad field
};

struct ColdStartTrial {
  SampledView view;
  bool posed = false;
  double cubeErrorPx = 0.0;  // when posed
  double ms = 0.0;           // the whole first frame (tracker.process), wall
  double cpuMs = 0.0;        // ... the thread's CPU time
  // The relocalisation attempt alone (Relocaliser::locate, no verification), as the tracker
  // reported it; negative when it made none.
  double relocaliseMs = -1.0, relocaliseCpuMs = -1.0;
  bool baselinePosed = false;
  double baselineErrorPx = 0.0, baselineMs = 0.0, baselineCpuMs = 0.0;
  std::string message;         // good / coarse / wrong / no pose
  std::string trackerMessage;  // what the tracker said about the frame (why no pose)
};

struct KidnapTrial {
  SampledView view;
  int recoveredOnFrame = 0;    // 1 or 2: the clear frame that gave a good pose; 0: neither
  double cubeErrorPx = 0.0;    // of the recovering pose
  int wrongPoses = 0;          // poses beyond wrongPx during the trial (black or clear frames)
  int posesOnBlack = 0;        // any pose on a black frame (there is nothing to see)
  std::string trackerMessage;  // the tracker's word on the clear frames ("; " between them)
};

struct RateSummary {
  int trials = 0, good = 0, wrong = 0;
  double goodPercent() const { return trials ? 100.0 * good / trials : 0.0; }
};

struct RelocalisationExperimentResult {
  double successPx = 1.5, wrongPx = 5.0;  // the options' thresholds
  std::vector<ColdStartTrial> coldStarts;
  std::vector<KidnapTrial> kidnaps;
  RateSummary coldStart() const, coldStartBaseline() const, kidnap() const;
  double medianColdStartMs() const, medianBaselineMs() const;
  // Medians over the cold starts that made a relocalisation attempt, and the baseline's over
  // the same views: wall and thread CPU milliseconds.
  double medianRelocaliseMs() const, medianRelocaliseCpuMs() const;
  double medianBaselineCpuMs() const, medianColdStartCpuMs() const;
};

// What a tracker reports for one frame: its pose (nullopt: none), what it said, and its
// relocalisation attempt's times (negative: it made none). Converts from a bare pose.
struct FrameOutcome {
  FrameOutcome() = default;
  FrameOutcome(std::optional<RigidPose> p) : pose(std::move(p)) {}  // implicit on purpose
  std::optional<RigidPose> pose;
  std::string message;
  double relocaliseMs = -1.0, relocaliseCpuMs = -1.0;
};

// A fresh tracker on `map` (the caller's choice of class and settings).
using FrameTracker = std::function<FrameOutcome(const cv::Mat& frame)>;
using TrackerFactory = std::function<FrameTracker()>;

// A fresh MultiReferenceTracker on `map` as a FrameTracker: its pose and message (with the
// relocaliser's, when it made an attempt) and the attempt's locate times.
FrameTracker multiReferenceFrameTracker(const MultiReferenceMap& map, const TrackerParams& params);

// Cube-vertex reprojection error (pixels, mean over the visible vertices) of `estimate`.
double poseCubeErrorPx(const PinholeCamera& camera, const RigidPose& truth,
                       const RigidPose& estimate, double cubeSide = 0.1);

// (c): milliseconds of each frame a tracker gives a pose for, both trackers over `frames` in
// order, frame by frame, taking turns at going first (both see the same machine load).
struct TrackedFrameTiming {
  std::vector<double> msFirst, msSecond;        // wall clock, tracked frames only
  std::vector<double> cpuMsFirst, cpuMsSecond;  // thread CPU, the same frames
};
TrackedFrameTiming compareTrackedFrameMs(const std::vector<cv::Mat>& frames,
                                         const FrameTracker& first, const FrameTracker& second);

// Runs (a) and (b); the views are drawn about sim.referencePoses() looking at sim.lookedAt().
// `map` feeds the baseline (its keypoint layers). Progress on stderr.
RelocalisationExperimentResult runRelocalisationExperiment(
    SceneSimulator& sim, const MultiReferenceMap& map, const TrackerFactory& makeTracker,
    const RelocalisationExperimentOptions& options);

}  // namespace reftrack::app
