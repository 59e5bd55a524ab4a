#pragma once
// GroundTruthBenchmark (`bench-real --input`): the 6-DOF tracker and its peers on any recording
// with a true camera pose per frame (GroundTruthSequence). A map is prepared from the reference
// frames with their true poses (MultiReferencePreparer, as `prepare --input --ref-frames --poses`
// does); then every method gives a pose per frame in each of the chosen frame orders (FrameOrder:
// by default in sequence order and in a shuffled order where every frame is a cold start, the
// tracker reset() before each frame, the Kalman filter restarted; the per-frame peers keep nothing
// anyway; the other orders play their frames as one sequence with no reset). Methods: reftrack
// (MultiReferenceTracker), SIFT / AKAZE / ORB + solvePnPRansac + solvePnPRefineLM from the same
// reference frames (PerFramePnpPeer), and ORB + PnP + Kalman (OrbPnpKalmanTracker on the first
// two references). Score: a cube (its base centred at cubeCentre in the world, extending to +z;
// or centred in front of the first reference's camera, scoringCube) projected with K alone (ideal
// pinhole): the mean pixel distance of its 8 vertices between the estimated and the true pose.
// Speed: the thread CPU time of each frame, every pass (the caller sets cv::setNumThreads(1)).
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/research/sixdof/FrameOrder.hpp"
#include "app/research/sixdof/GroundTruthSequence.hpp"
#include "app/research/sixdof/PerFramePeerPoses.hpp"
#include "engine/config/TrackerParams.hpp"
#include "engine/reference/ReferencePreparer.hpp"
#include "engine/relocalisation/RecoveryStage.hpp"

namespace reftrack::app {

// Poses farther off than this are wrong (they draw the content in the wrong place) ...
inline constexpr double kWrongPosePx = 5.0;
// ... and poses within this are good (the shuffled-frames target).
inline constexpr double kGoodPosePx = 1.5;

// The methods, by their `--methods` names, in table order.
const std::vector<std::string>& groundTruthBenchmarkMethods();  // reftrack sift akaze orb kalman

struct GroundTruthBenchmarkOptions {
  std::vector<int> references;  // frame indices of the reference images (>= 2, distinct)
  Eigen::Vector3d cubeCentre = Eigen::Vector3d::Zero();  // centre of the cube's base (world, m)
  double cubeEdge = 0.1;                                 // metres
  // > 0: the cube is centred this far (m) in front of the first reference's camera instead, on
  // its optical axis, its edges along that camera's axes (a scene without a known plane: the
  // world frame of a depth-camera trajectory is arbitrary); cubeCentre is then not used.
  double cubeInFrontM = 0.0;
  // A map the preparation refuses: true, reftrack and the Kalman baseline give no frame a pose
  // (the reason in their noPose, the message in the result's mapError) and the peers still run;
  // false: runGroundTruthBenchmark throws.
  bool mapFailureIsLoss = false;
  // Set: each per-frame peer named in `methods` (sift, akaze, orb) is not played in every order
  // and pass: this gives its poses over all the sequence's frames once (computePeerPoses, or a
  // PeerPoseCache), with the reference indices, and every order replays them (replayPeerPoses:
  // a per-frame peer gives a frame the same pose in any order; its CPU times are that run's).
  // Unset: the peers are played like the other methods. Not with away:N orders.
  std::function<PeerPoses(const std::string& detector, const std::vector<int>& references)>
      peerPoses;
  int frames = 0;  // frames benchmarked from the start; 0: every frame of the sequence
  int passes = 1;  // passes over the frames for the timing (errors from the first)
  std::uint64_t shuffleSeed = 1;  // of the shuffled orders (shuffled, shuffled-sequence, cuts:N)
  std::vector<std::string> methods = groundTruthBenchmarkMethods();
  std::vector<std::string> orders = defaultFrameOrders();  // `--order` names, in table order
  // away:N orders: frames of another scene (any size: resized to the sequence's), played in
  // turn; `awayDescription` names them in the table.
  std::vector<cv::Mat> awayFrames;
  std::string awayDescription;

  // Throws reftrack::Error naming the bad option (before anything is read), also an away:N
  // order with neither awayFrames nor an awayDescription (the source still to be read). An order's
  // N or K beyond the frames is checked by runGroundTruthBenchmark (planFrames), before the map.
  void check() const;
};

// One method over the frames in one order.
struct MethodRun {
  std::string method;  // its name in the table, e.g. "SIFT+PnP"
  FrameOrder order;
  FramePlan plan;  // the frames played, in the order played (the same every pass)
  // Per frame index (not processing order), first pass: the cube error, NaN without a pose;
  // frames without a true pose or not played are NaN too.
  std::vector<double> errorPx;
  std::vector<std::optional<RigidPose>> poses;  // per frame index, first pass: world->camera
  // Per position in plan.frames, first pass: the cube error (NaN without a pose) and whether the
  // play is scored (a frame of the sequence with a true pose). Orders that repeat frames
  // (return:) are scored per play; errorPx and poses then hold a frame's last play.
  std::vector<double> playedErrorPx;
  std::vector<bool> playedScored;
  std::vector<double> cpuMs;  // every played frame, every pass
  // away:N: the frames of the other scene given a pose (every one is wrong; first pass) and
  // their thread CPU times (every pass; also in cpuMs).
  int awayPosed = 0;
  std::vector<double> awayCpuMs;
  std::map<std::string, int> noPose;  // reason -> played frames with a true pose but none estimated
  // reftrack only, first pass, every played frame: what stopped each start near a reference and
  // each relocalisation attempt (RecoveryStage names -> count), and the thread CPU of each
  // relocalisation attempt with its verification.
  std::map<std::string, int> startStops, searchStops;
  std::vector<double> searchCpuMs;
  // reftrack only (NaN elsewhere), per frame index, first pass: the cube error its covariance
  // predicts (MultiReferenceResult::predictedErrorPx for the scoring cube), and whether the frame
  // was reported uncertain (pose.max_predicted_error_px).
  std::vector<double> predictedErrorPx;
  std::vector<bool> uncertain;
};

struct MethodSummary {
  int frames = 0;  // played frames with a true pose (the scored frames)
  int posed = 0;   // ... of them given a pose
  // Over the posed frames with a finite error (NaN when none).
  double meanPx = NAN, p95Px = NAN, maxPx = NAN;
  int behind = 0;  // posed frames whose pose put the whole cube behind the camera (infinite error)
  int wrong = 0;   // posed frames more than kWrongPosePx off (those behind included)
  int good = 0;    // posed frames within kGoodPosePx
  double cpuMedianMs = NAN;  // median thread CPU per processed frame
  double coveragePercent() const { return frames > 0 ? 100.0 * posed / frames : 0.0; }
};

// The cube errors of the scored plays (NaN: no pose): per frame index with a true pose played by
// run.plan, or per play when the plan repeats frames (return: orders).
std::vector<double> scoredErrors(const MethodRun& run, const std::vector<bool>& truth);

// `truth[k]`: frame k has a true pose (frames without one, or not in run.plan, are not scored).
MethodSummary summarise(const MethodRun& run, const std::vector<bool>& truth);

// How a method came back after one cut of a cuts:N order.
struct CutRecovery {
  std::size_t position = 0;        // in the plan: the first frame after the cut
  int fromFrame = 0, toFrame = 0;  // the frames played just before and just after the cut
  int segmentFrames = 0;           // frames from the cut to the next cut (or the end)
  // Frames after the cut before the first pose within kGoodPosePx (re-acquired within k frames;
  // 0: the first frame after the cut is already good); -1: none in the segment.
  int framesToReacquire = -1;
  int wrong = 0;  // poses more than kWrongPosePx off from the cut to the next cut (or the end)
};

// Per cut of run.plan (none unless the order has cuts), from run.errorPx.
std::vector<CutRecovery> cutRecoveries(const MethodRun& run);

// How a method came back after an away:N order's other scene: frames after the return before
// the first pose within kGoodPosePx (-1: never), and the poses more than kWrongPosePx off after.
struct AwayReturn {
  int framesToReacquire = -1;
  int wrongAfter = 0;
};
AwayReturn awayReturn(const MethodRun& run);

// One range of a return: order as a method played it (first pass; CPU over every pass).
struct RangeOutcome {
  FrameRange range;
  int frames = 0;                        // plays with a true pose
  int posed = 0, within = 0, wrong = 0;  // ... posed; within kWrongPosePx; more than wrongPx off
  // Plays from the range's start to the first pose within kWrongPosePx (0: its first frame);
  // -1: none in the range.
  int framesToReacquire = -1;
  double cpuMeanMs = NAN;  // mean thread CPU per played frame of the range
};
// Per range of a return: order (none for the other orders); `wrongPx`: the wrong threshold.
std::vector<RangeOutcome> rangeOutcomes(const MethodRun& run, double wrongPx);

// Calibration of the predicted error (issue 32) over the posed frames with a true pose and a
// prediction: true / predicted cube error per frame, and the predictions themselves.
struct PredictionSummary {
  int frames = 0;  // posed frames with a finite true error and a prediction
  double ratioMedian = NAN, ratioP25 = NAN, ratioP75 = NAN;  // true / predicted
  double predictedMedianPx = NAN, predictedP95Px = NAN, predictedMaxPx = NAN;
  int uncertain = 0;                 // frames reported uncertain
  double uncertainTrueMeanPx = NAN;  // ... their mean true error
  int wrongNotUncertain = 0;         // posed frames > kWrongPosePx off not reported uncertain
};
PredictionSummary summarisePrediction(const MethodRun& run, const std::vector<bool>& truth);

struct GroundTruthBenchmarkResult {
  std::string framesDescription, groundTruthDescription;
  cv::Size frameSize;
  int frames = 0;           // benchmarked (the first `frames` of the sequence)
  std::vector<bool> truth;  // per benchmarked frame: has a true pose
  std::vector<int> references;
  std::vector<double> referenceDistancesMm;  // camera centre of reference i from reference 0's
  int firstFrame = 0;  // the input's index of frame 0 (GroundTruthSequence::firstFrame)
  Eigen::Vector3d cubeCentre = Eigen::Vector3d::Zero();
  double cubeEdge = 0.0;
  double cubeInFrontM = 0.0;          // as in the options
  std::vector<Eigen::Vector3d> cube;  // the scored cube's 8 vertices (world)
  std::string mapError;               // the preparation's refusal (options.mapFailureIsLoss)
  std::uint64_t shuffleSeed = 0;
  int passes = 0;
  double fps = 30.0;  // the sequence's frame rate (its timestamps; 30 when they do not tell)
  std::string awayDescription;                                 // away:N orders: the other scene
  int mapPoints = 0, mapKeypoints = 0, mapKeypointPoints = 0;  // reftrack's map
  std::vector<std::pair<std::string, int>> modelPoints;  // peers' triangulated points, by method
  std::vector<FrameOrder> orders;                        // as options.orders named them
  std::vector<MethodRun> runs;  // per method in table order, then per order
  double seconds = 0.0;         // wall time of the preparation and every run
};

// Progress lines (one per method and order) for the caller to print.
using BenchmarkProgress = std::function<void(const std::string&)>;

// One method behind a common face: a pose for a frame (or the reason there is none), a cold
// start, and a fresh state for a new run.
class PoseMethod {
 public:
  virtual ~PoseMethod() = default;
  virtual std::string name() const = 0;
  virtual void startRun() = 0;   // before a run over the frames (outside the timing)
  virtual void coldStart() = 0;  // before each frame of a cold-start order (outside the timing)
  // The world->camera pose of `frame`, or nullopt with `reason` set.
  virtual std::optional<RigidPose> locate(const cv::Mat& frame, std::string& reason) = 0;
  // The last located frame's predicted cube error, and whether it was reported uncertain
  // (reftrack only).
  virtual double predictedErrorPx() const { return NAN; }
  virtual bool uncertain() const { return false; }
  // The last located frame's ways back (reftrack only): what stopped the start near a reference
  // and the relocalisation attempt (None: not tried), and that attempt's thread CPU.
  virtual RecoveryStage lastStart() const { return RecoveryStage::None; }
  virtual RecoveryStage lastSearch() const { return RecoveryStage::None; }
  virtual double lastSearchCpuMs() const { return NAN; }
};

// One pass of `method` over run.plan: startRun(), then each planned frame of `sequence` in turn
// (coldStart() before each only when the plan says so), its thread CPU time appended to
// run.cpuMs; with `score` (the first pass) each frame's pose, cube error against its true pose
// and the reasons for no pose are recorded too (run.errorPx and run.poses hold every frame index).
// Away frames (plan index -1 - j) come from away[j % away.size()].
void playFrames(PoseMethod& method, const GroundTruthSequence& sequence,
                const std::vector<Eigen::Vector3d>& cube, bool score, MethodRun& run,
                const std::vector<cv::Mat>& away = {});

// `peer`'s poses of the frames of run.plan (frame indices of `sequence`) scored against their
// true poses as playFrames does (first pass): run.poses, errorPx, noPose, and cpuMs (the peer's
// CPU time of each played frame). Throws reftrack::Error for an away:N plan.
void replayPeerPoses(const PeerPoses& peer, const GroundTruthSequence& sequence,
                     const std::vector<Eigen::Vector3d>& cube, MethodRun& run);

// The mean pixel distance of the cube's vertices between `estimate` and `truth` (world->camera),
// projected with K alone; vertices behind either camera are left out, and a pose that leaves
// none in front of both is infinitely wrong.
double cubeErrorPx(const PinholeCamera& camera, const std::vector<Eigen::Vector3d>& cube,
                   const RigidPose& truth, const RigidPose& estimate);
// The 8 vertices of the cube of `edge` whose base is centred at `baseCentre` on z = 0, up to +z.
std::vector<Eigen::Vector3d> cubeOn(const Eigen::Vector3d& baseCentre, double edge);
// The 8 vertices (world) of the cube of `edge` centred `distance` in front of the camera of
// `worldToCamera` on its optical axis, its edges along the camera's axes.
std::vector<Eigen::Vector3d> cubeInFrontOf(const RigidPose& worldToCamera, double distance,
                                           double edge);
// The scored cube of `options` on `sequence` (cubeOn, or cubeInFrontOf the first reference's
// true pose); the first reference must have one.
std::vector<Eigen::Vector3d> scoringCube(const GroundTruthBenchmarkOptions& options,
                                         const GroundTruthSequence& sequence);

// Throws reftrack::Error when a reference frame is beyond the sequence or has no true pose, when
// options.frames exceeds the sequence, or when the preparation or a peer's model fails.
GroundTruthBenchmarkResult runGroundTruthBenchmark(const GroundTruthSequence& sequence,
                                                   const GroundTruthBenchmarkOptions& options,
                                                   const TrackerParams& params,
                                                   const ReferencePreparerParams& prepareParams,
                                                   const BenchmarkProgress& progress = {});

}  // namespace reftrack::app
