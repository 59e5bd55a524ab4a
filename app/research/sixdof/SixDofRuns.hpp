#pragma once
// Runs of the 6-DOF PoseTracker (standard or regularised) and of the ORB + PnP + Kalman baseline
// over a SimulatedSequence, timed per frame on the calling thread, with the evaluation against
// ground truth (TrajectoryEvaluator: cube-vertex error, jitter, ATE) and the drift check.
#include <map>
#include <string>
#include <vector>

#include "app/research/sixdof/SimulatedSequence.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/estimation/MotionModel.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"

namespace reftrack::app {

struct TrackerRun {
  std::string name;
  TumTrajectory estimate;          // frames with a pose only
  std::vector<double> frameMs;     // every frame (wall clock)
  std::vector<double> frameCpuMs;  // every frame, thread CPU time (ThreadCpuClock.hpp)
  std::map<std::string, std::vector<double>> stageMs;  // PoseTracker stages
  std::vector<std::optional<Vector6d>> motion;         // x_Ak per frame (PoseTracker runs)
  int lostFrames = 0;
  std::vector<std::string> lostReasons;  // "frame k: why", PoseTracker runs
  TrajectoryEvaluation evaluation;
  double firstHundredMeanPx = 0, lastHundredMeanPx = 0;  // drift check: mean cube error
  double staticJitterPx = 0;           // SD over time of the cube vertices' image positions
  std::map<std::string, int> pairUse;  // MultiReferenceTracker runs: tracked frames per "a-b"
};

// `motion` replaces the AR model and Q of `params` when given (e.g. fitted by fit-motion).
TrackerRun runPoseTracker(const SimulatedSequence& s, const TrackerParams& params,
                          const std::string& name, const std::optional<ArMotionModel>& motion = {},
                          double cubeSide = 0.1);
// The MultiReferenceTracker over s.references (every reference view of the sequence); throws
// reftrack::Error when the sequence was prepared without them. `motion` as above.
TrackerRun runMultiReferenceTracker(const SimulatedSequence& s, const TrackerParams& params,
                                    const std::string& name,
                                    const std::optional<ArMotionModel>& motion = {},
                                    double cubeSide = 0.1);
TrackerRun runOrbBaseline(const SimulatedSequence& s, double cubeSide = 0.1);

double median(std::vector<double> v);

}  // namespace reftrack::app
