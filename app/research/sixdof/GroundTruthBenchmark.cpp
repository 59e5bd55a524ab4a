#include "app/research/sixdof/GroundTruthBenchmark.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <set>

#include "app/research/baselines/OrbPnpKalmanTracker.hpp"
#include "app/research/baselines/PerFramePnpPeer.hpp"
#include "app/research/sixdof/RealFootageBenchmark.hpp"
#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/evaluation/TrajectoryEvaluator.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack::app {

const std::vector<std::string>& groundTruthBenchmarkMethods() {
  static const std::vector<std::string> methods = {"reftrack", "sift", "akaze", "orb", "kalman"};
  return methods;
}

void GroundTruthBenchmarkOptions::check() const {
  if (references.size() < 2)
    throw Error("bench-real: --ref-frames needs at least two frames, got " +
                std::to_string(references.size()));
  std::set<int> seen;
  for (int r : references) {
    if (r < 0) throw Error("bench-real: --ref-frames: frame " + std::to_string(r) + " is < 0");
    if (!seen.insert(r).second)
      throw Error("bench-real: --ref-frames: frame " + std::to_string(r) + " given twice");
  }
  if (!cubeCentre.allFinite()) throw Error("bench-real: --cube-centre must be finite");
  if (!(cubeEdge > 0) || !std::isfinite(cubeEdge))
    throw Error("bench-real: --cube-edge must be > 0 m");
  if (!(cubeInFrontM >= 0) || !std::isfinite(cubeInFrontM))
    throw Error("bench-real: the cube's distance in front of the reference must be >= 0 m");
  if (cubeInFrontM > 0 && cubeInFrontM <= 0.5 * cubeEdge)
    throw Error("bench-real: a cube " + std::to_string(cubeInFrontM) +
                " m in front of the reference with an edge of " + std::to_string(cubeEdge) +
                " m reaches behind the camera");
  if (frames < 0) throw Error("bench-real: --frames must be >= 0 (0: every frame)");
  if (passes < 1) throw Error("bench-real: --passes must be >= 1");
  for (const FrameOrder& order : parseFrameOrders(orders)) {
    if (order.kind == FrameOrderKind::Away && awayFrames.empty() && awayDescription.empty())
      throw Error("bench-real: --order " + order.name +
                  " needs the other scene's frames (--away-input)");
    if (order.kind == FrameOrderKind::Away && peerPoses)
      throw Error("bench-real: --order " + order.name +
                  ": the per-frame peers' replayed poses cover the sequence's frames only");
  }
  for (const cv::Mat& f : awayFrames)
    if (f.empty() || f.type() != CV_8UC3)
      throw Error("bench-real: --away-input: a frame is empty or not 8-bit BGR");
  if (methods.empty()) throw Error("bench-real: --methods names no method");
  const std::vector<std::string>& known = groundTruthBenchmarkMethods();
  std::set<std::string> named;
  for (const std::string& m : methods) {
    if (std::find(known.begin(), known.end(), m) == known.end())
      throw Error("bench-real: --methods: unknown method '" + m +
                  "' (known: reftrack, sift, akaze, orb, kalman)");
    if (!named.insert(m).second) throw Error("bench-real: --methods: '" + m + "' given twice");
  }
}

std::vector<double> scoredErrors(const MethodRun& run, const std::vector<bool>& truth) {
  std::vector<double> out;
  if (run.plan.repeatsFrames) {
    for (std::size_t i = 0; i < run.playedErrorPx.size() && i < run.playedScored.size(); ++i)
      if (run.playedScored[i]) out.push_back(run.playedErrorPx[i]);
    return out;
  }
  const std::vector<bool> played = playedFrames(run.plan, static_cast<int>(truth.size()));
  for (std::size_t k = 0; k < truth.size() && k < run.errorPx.size(); ++k)
    if (truth[k] && played[k]) out.push_back(run.errorPx[k]);
  return out;
}

MethodSummary summarise(const MethodRun& run, const std::vector<bool>& truth) {
  MethodSummary s;
  std::vector<double> errors;
  for (const double e : scoredErrors(run, truth)) {
    ++s.frames;
    if (std::isnan(e)) continue;
    ++s.posed;
    s.wrong += e > kWrongPosePx ? 1 : 0;
    s.good += e <= kGoodPosePx ? 1 : 0;
    if (std::isinf(e))
      ++s.behind;
    else
      errors.push_back(e);
  }
  if (!errors.empty()) {
    s.meanPx =
        std::accumulate(errors.begin(), errors.end(), 0.0) / static_cast<double>(errors.size());
    s.p95Px = percentileOf(errors, 0.95);
    s.maxPx = *std::max_element(errors.begin(), errors.end());
  }
  s.cpuMedianMs = percentileOf(run.cpuMs, 0.5);
  return s;
}

std::vector<CutRecovery> cutRecoveries(const MethodRun& run) {
  std::vector<CutRecovery> recoveries;
  const std::vector<int>& frames = run.plan.frames;
  for (std::size_t c = 0; c < run.plan.cuts.size(); ++c) {
    CutRecovery r;
    r.position = run.plan.cuts[c];
    if (r.position == 0 || r.position >= frames.size()) continue;  // not a cut between frames
    const std::size_t end = c + 1 < run.plan.cuts.size() ? run.plan.cuts[c + 1] : frames.size();
    r.fromFrame = frames[r.position - 1];
    r.toFrame = frames[r.position];
    r.segmentFrames = static_cast<int>(end - r.position);
    for (std::size_t i = r.position; i < end; ++i) {
      const std::size_t k = static_cast<std::size_t>(frames[i]);
      const double e = k < run.errorPx.size() ? run.errorPx[k] : NAN;
      if (e > kWrongPosePx) ++r.wrong;
      if (r.framesToReacquire < 0 && e <= kGoodPosePx)
        r.framesToReacquire = static_cast<int>(i - r.position);
    }
    recoveries.push_back(r);
  }
  return recoveries;
}

AwayReturn awayReturn(const MethodRun& run) {
  AwayReturn r;
  const std::vector<int>& frames = run.plan.frames;
  if (run.plan.awayEnd <= run.plan.awayStart) return r;
  for (std::size_t i = run.plan.awayEnd; i < frames.size(); ++i) {
    const std::size_t k = static_cast<std::size_t>(frames[i]);
    const double e = k < run.errorPx.size() ? run.errorPx[k] : NAN;
    if (e > kWrongPosePx) ++r.wrongAfter;
    if (r.framesToReacquire < 0 && e <= kGoodPosePx)
      r.framesToReacquire = static_cast<int>(i - run.plan.awayEnd);
  }
  return r;
}

std::vector<RangeOutcome> rangeOutcomes(const MethodRun& run, double wrongPx) {
  std::vector<RangeOutcome> out;
  if (run.order.kind != FrameOrderKind::Return) return out;
  const std::vector<std::size_t>& starts = run.plan.rangeStarts;
  const std::size_t plays = run.plan.frames.size();
  for (std::size_t r = 0; r < starts.size() && r < run.order.ranges.size(); ++r) {
    RangeOutcome o;
    o.range = run.order.ranges[r];
    const std::size_t end = r + 1 < starts.size() ? starts[r + 1] : plays;
    for (std::size_t i = starts[r]; i < end && i < run.playedScored.size(); ++i) {
      if (!run.playedScored[i]) continue;
      ++o.frames;
      const double e = run.playedErrorPx[i];
      if (std::isnan(e)) continue;
      ++o.posed;
      o.within += e <= kWrongPosePx ? 1 : 0;
      o.wrong += e > wrongPx ? 1 : 0;
      if (o.framesToReacquire < 0 && e <= kWrongPosePx)
        o.framesToReacquire = static_cast<int>(i - starts[r]);
    }
    // cpuMs holds every pass's plays one after the other.
    double sum = 0.0;
    int n = 0;
    for (std::size_t pass = 0; plays > 0 && (pass + 1) * plays <= run.cpuMs.size(); ++pass)
      for (std::size_t i = starts[r]; i < end; ++i, ++n) sum += run.cpuMs[pass * plays + i];
    if (n > 0) o.cpuMeanMs = sum / n;
    out.push_back(o);
  }
  return out;
}

PredictionSummary summarisePrediction(const MethodRun& run, const std::vector<bool>& truth) {
  PredictionSummary s;
  std::vector<double> ratios, predicted, uncertainErrors;
  for (std::size_t k = 0; k < truth.size() && k < run.predictedErrorPx.size(); ++k) {
    const double e = run.errorPx[k], p = run.predictedErrorPx[k];
    if (!truth[k] || std::isnan(e)) continue;
    const bool uncertain = k < run.uncertain.size() && run.uncertain[k];
    if (uncertain) uncertainErrors.push_back(e);
    s.wrongNotUncertain += e > kWrongPosePx && !uncertain ? 1 : 0;
    if (!std::isfinite(e) || !(p > 0)) continue;
    ratios.push_back(e / p);
    predicted.push_back(p);
  }
  s.frames = static_cast<int>(ratios.size());
  s.uncertain = static_cast<int>(uncertainErrors.size());
  if (!uncertainErrors.empty())
    s.uncertainTrueMeanPx = std::accumulate(uncertainErrors.begin(), uncertainErrors.end(), 0.0) /
                            static_cast<double>(uncertainErrors.size());
  if (ratios.empty()) return s;
  s.ratioMedian = percentileOf(ratios, 0.5);
  s.ratioP25 = percentileOf(ratios, 0.25);
  s.ratioP75 = percentileOf(ratios, 0.75);
  s.predictedMedianPx = percentileOf(predicted, 0.5);
  s.predictedP95Px = percentileOf(predicted, 0.95);
  s.predictedMaxPx = *std::max_element(predicted.begin(), predicted.end());
  return s;
}

std::vector<Eigen::Vector3d> cubeOn(const Eigen::Vector3d& baseCentre, double edge) {
  std::vector<Eigen::Vector3d> cube = cubeVertices(edge);
  for (Eigen::Vector3d& v : cube) v += baseCentre;
  return cube;
}

std::vector<Eigen::Vector3d> cubeInFrontOf(const RigidPose& worldToCamera, double distance,
                                           double edge) {
  const RigidPose cameraToWorld = worldToCamera.inverse();
  std::vector<Eigen::Vector3d> cube;
  for (const Eigen::Vector3d& v : cubeVertices(edge))  // base centred at 0, up to +z
    cube.push_back(cameraToWorld * Eigen::Vector3d(v.x(), v.y(), distance + v.z() - 0.5 * edge));
  return cube;
}

std::vector<Eigen::Vector3d> scoringCube(const GroundTruthBenchmarkOptions& o,
                                         const GroundTruthSequence& s) {
  if (o.cubeInFrontM <= 0) return cubeOn(o.cubeCentre, o.cubeEdge);
  const std::size_t first = static_cast<std::size_t>(o.references.at(0));
  if (first >= s.truth.size() || !s.truth[first])
    throw Error("bench-real: the cube is placed in front of reference frame " +
                std::to_string(s.firstFrame + o.references.at(0)) + ", which has no true pose");
  return cubeInFrontOf(*s.truth[first], o.cubeInFrontM, o.cubeEdge);
}

double cubeErrorPx(const PinholeCamera& camera, const std::vector<Eigen::Vector3d>& cube,
                   const RigidPose& truth, const RigidPose& estimate) {
  double sum = 0.0;
  int n = 0;
  for (const Eigen::Vector3d& X : cube) {
    const Eigen::Vector3d a = truth * X, b = estimate * X;
    if (!(a.z() > 0) || !(b.z() > 0)) continue;  // behind a camera: no image position
    sum += (camera.project(a) - camera.project(b)).norm();
    ++n;
  }
  return n > 0 ? sum / n : INFINITY;
}

namespace {

class ReftrackMethod final : public PoseMethod {
 public:
  ReftrackMethod(const MultiReferenceMap& map, const TrackerParams& params,
                 std::vector<Eigen::Vector3d> cube)
      : map_(map), params_(params), cube_(std::move(cube)) {}
  std::string name() const override { return "reftrack"; }
  void startRun() override {
    tracker_ = std::make_unique<MultiReferenceTracker>(map_, params_);
    tracker_->setOverlayPoints(cube_);  // the predicted error is the scoring cube's
  }
  void coldStart() override { tracker_->reset(); }
  double predictedErrorPx() const override { return predicted_; }
  bool uncertain() const override { return uncertain_; }
  RecoveryStage lastStart() const override { return start_; }
  RecoveryStage lastSearch() const override { return search_; }
  double lastSearchCpuMs() const override { return searchCpuMs_; }
  std::optional<RigidPose> locate(const cv::Mat& frame, std::string& reason) override {
    const MultiReferenceResult multi = tracker_->process(frame);
    predicted_ = multi.predictedErrorPx.value_or(NAN);
    uncertain_ = multi.uncertain;
    start_ = multi.start;
    search_ = multi.relocalisation.attempted ? multi.relocalisation.stop : RecoveryStage::None;
    searchCpuMs_ = multi.relocalisation.attempted ? multi.relocalisation.cpuMs : NAN;
    const PoseTrackingResult& r = multi.tracking;
    if (r.state == TrackingState::Tracking && r.worldToCamera) return r.worldToCamera;
    reason = r.message.substr(0, r.message.find(" ("));
    if (reason.empty()) reason = toString(r.state);
    return std::nullopt;
  }

 private:
  const MultiReferenceMap& map_;
  TrackerParams params_;
  std::vector<Eigen::Vector3d> cube_;
  std::unique_ptr<MultiReferenceTracker> tracker_;
  double predicted_ = NAN;
  bool uncertain_ = false;
  RecoveryStage start_ = RecoveryStage::None, search_ = RecoveryStage::None;
  double searchCpuMs_ = NAN;
};

class PeerMethod final : public PoseMethod {
 public:
  PeerMethod(const std::string& detector, const GroundTruthSequence& s,
             const std::vector<int>& references)
      : peer_(detector, s.camera, imagesOf(s, references), posesOf(s, references)),
        name_(perFramePnpPeerName(detector)) {}
  std::string name() const override { return name_; }
  void startRun() override {}
  void coldStart() override {}
  std::optional<RigidPose> locate(const cv::Mat& frame, std::string& reason) override {
    const PerFramePnpResult r = peer_.locate(frame);
    if (!r.worldToCamera) reason = peer_.noPoseReason(r);
    return r.worldToCamera;
  }
  int modelPoints() const { return peer_.modelPoints(); }

  static std::vector<cv::Mat> imagesOf(const GroundTruthSequence& s, const std::vector<int>& refs) {
    std::vector<cv::Mat> images;
    for (int r : refs) images.push_back(s.frames[static_cast<std::size_t>(r)]);
    return images;
  }
  static std::vector<RigidPose> posesOf(const GroundTruthSequence& s,
                                        const std::vector<int>& refs) {
    std::vector<RigidPose> poses;
    for (int r : refs) poses.push_back(*s.truth[static_cast<std::size_t>(r)]);
    return poses;
  }

 private:
  PerFramePnpPeer peer_;
  std::string name_;
};

class KalmanMethod final : public PoseMethod {
 public:
  KalmanMethod(ReferenceMap pair, double fps) : pair_(std::move(pair)) {
    params_.dt = 1.0 / fps;
    startRun();
  }
  std::string name() const override { return "ORB+PnP+Kalman"; }
  void startRun() override { tracker_ = std::make_unique<OrbPnpKalmanTracker>(pair_, params_); }
  void coldStart() override { tracker_->reset(); }
  std::optional<RigidPose> locate(const cv::Mat& frame, std::string& reason) override {
    std::optional<RigidPose> pose = tracker_->process(frame);
    if (!pose) reason = "no PnP pose with enough inliers yet";
    return pose;
  }
  int modelPoints() const { return tracker_->modelPoints(); }

 private:
  ReferenceMap pair_;
  OrbPnpKalmanParams params_;
  std::unique_ptr<OrbPnpKalmanTracker> tracker_;
};

// A method that gives no frame a pose, the reason given: reftrack or the Kalman baseline without
// their map (the preparation refused it); the stand-in of a replayed peer (never played).
class NoPoseMethod final : public PoseMethod {
 public:
  NoPoseMethod(std::string name, std::string reason)
      : name_(std::move(name)), reason_(std::move(reason)) {}
  std::string name() const override { return name_; }
  void startRun() override {}
  void coldStart() override {}
  std::optional<RigidPose> locate(const cv::Mat&, std::string& reason) override {
    reason = reason_;
    return std::nullopt;
  }

 private:
  std::string name_, reason_;
};

// The sequence's nominal frame rate from its timestamps (30 when they do not tell).
double frameRate(const std::vector<double>& timestamps) {
  if (timestamps.size() < 2) return 30.0;
  const double span = timestamps.back() - timestamps.front();
  const double fps = static_cast<double>(timestamps.size() - 1) / span;
  return std::isfinite(fps) && fps > 0 ? fps : 30.0;
}

}  // namespace

void playFrames(PoseMethod& method, const GroundTruthSequence& s,
                const std::vector<Eigen::Vector3d>& cube, bool score, MethodRun& run,
                const std::vector<cv::Mat>& away) {
  method.startRun();
  if (score) {
    run.playedErrorPx.assign(run.plan.frames.size(), NAN);
    run.playedScored.assign(run.plan.frames.size(), false);
  }
  for (std::size_t position = 0; position < run.plan.frames.size(); ++position) {
    const int k = run.plan.frames[position];
    if (run.plan.coldStarts) method.coldStart();
    std::string reason;
    // What the method's ways back did on the frame (reftrack), counted on the scored pass.
    const auto countStops = [&] {
      if (!score) return;
      if (method.lastStart() != RecoveryStage::None) ++run.startStops[toString(method.lastStart())];
      if (method.lastSearch() != RecoveryStage::None) {
        ++run.searchStops[toString(method.lastSearch())];
        run.searchCpuMs.push_back(method.lastSearchCpuMs());
      }
    };
    if (k < 0) {  // the other scene: no true pose, so any pose is wrong
      if (away.empty()) throw Error("bench-real: an away:N order without the other scene's frames");
      const double cpu0 = threadCpuMs();
      const bool posed =
          method.locate(away[static_cast<std::size_t>(-1 - k) % away.size()], reason).has_value();
      run.cpuMs.push_back(threadCpuMs() - cpu0);
      run.awayCpuMs.push_back(run.cpuMs.back());
      if (score && posed) ++run.awayPosed;
      countStops();
      continue;
    }
    const std::size_t frame = static_cast<std::size_t>(k);
    const double cpu0 = threadCpuMs();
    const std::optional<RigidPose> pose = method.locate(s.frames[frame], reason);
    run.cpuMs.push_back(threadCpuMs() - cpu0);
    countStops();
    if (!score) continue;
    run.poses[frame] = pose;
    if (frame < run.predictedErrorPx.size())
      run.predictedErrorPx[frame] = method.predictedErrorPx();
    if (frame < run.uncertain.size()) run.uncertain[frame] = method.uncertain();
    const std::optional<RigidPose>& truth = s.truth[frame];
    if (!truth) continue;
    run.playedScored[position] = true;
    if (pose) {
      run.errorPx[frame] = cubeErrorPx(s.camera, cube, *truth, *pose);
      run.playedErrorPx[position] = run.errorPx[frame];
    } else {
      run.errorPx[frame] = NAN;  // a repeated frame keeps its last play
      ++run.noPose[reason];
    }
  }
}

void replayPeerPoses(const PeerPoses& peer, const GroundTruthSequence& s,
                     const std::vector<Eigen::Vector3d>& cube, MethodRun& run) {
  run.playedErrorPx.assign(run.plan.frames.size(), NAN);
  run.playedScored.assign(run.plan.frames.size(), false);
  for (std::size_t position = 0; position < run.plan.frames.size(); ++position) {
    const int k = run.plan.frames[position];
    if (k < 0) throw Error("bench-real: a per-frame peer's poses cannot be replayed in away:N");
    const std::size_t frame = static_cast<std::size_t>(k);
    run.cpuMs.push_back(peer.cpuMs.at(frame));
    if (frame >= run.poses.size()) continue;
    run.poses[frame] = peer.poses[frame];
    const std::optional<RigidPose>& truth = s.truth[frame];
    if (!truth) continue;
    run.playedScored[position] = true;
    if (peer.poses[frame]) {
      run.errorPx[frame] = cubeErrorPx(s.camera, cube, *truth, *peer.poses[frame]);
      run.playedErrorPx[position] = run.errorPx[frame];
    } else {
      ++run.noPose[peer.reasons[frame]];
    }
  }
}

GroundTruthBenchmarkResult runGroundTruthBenchmark(const GroundTruthSequence& s,
                                                   const GroundTruthBenchmarkOptions& o,
                                                   const TrackerParams& params,
                                                   const ReferencePreparerParams& prepareParams,
                                                   const BenchmarkProgress& progress) {
  o.check();
  const auto start = std::chrono::steady_clock::now();
  const int available = static_cast<int>(s.frames.size());
  if (o.frames > available)
    throw Error("bench-real: --frames " + std::to_string(o.frames) + " but " + s.framesDescription +
                " holds " + std::to_string(available) + " frames");
  for (int r : o.references) {  // named by the input's frame index
    const std::string frame = std::to_string(s.firstFrame + r);
    if (r >= available)
      throw Error("bench-real: reference frame " + frame + " is beyond the " +
                  std::to_string(available) + " frames of " + s.framesDescription +
                  (s.firstFrame > 0 ? " read from frame " + std::to_string(s.firstFrame) + " on"
                                    : std::string()));
    if (!s.truth[static_cast<std::size_t>(r)])
      throw Error("bench-real: reference frame " + frame + " has no ground-truth pose (" +
                  s.groundTruthDescription + ")");
  }
  GroundTruthBenchmarkResult result;
  result.framesDescription = s.framesDescription;
  result.groundTruthDescription = s.groundTruthDescription;
  result.frameSize = s.camera.imageSize();
  result.frames = o.frames > 0 ? o.frames : available;
  for (int k = 0; k < result.frames; ++k)
    result.truth.push_back(s.truth[static_cast<std::size_t>(k)].has_value());
  result.references = o.references;
  result.firstFrame = s.firstFrame;
  result.cubeCentre = o.cubeCentre;
  result.cubeEdge = o.cubeEdge;
  result.cubeInFrontM = o.cubeInFrontM;
  result.cube = scoringCube(o, s);
  result.shuffleSeed = o.shuffleSeed;
  result.passes = o.passes;
  result.fps = frameRate(s.timestamps);
  result.awayDescription = o.awayDescription;
  for (const FrameOrder& order : result.orders)
    if (order.kind == FrameOrderKind::Away && o.awayFrames.empty())
      throw Error("bench-real: --order " + order.name + ": " + o.awayDescription +
                  " gave no frame");
  std::vector<cv::Mat> away;  // the other scene at the sequence's frame size
  for (const cv::Mat& f : o.awayFrames) {
    if (f.size() == s.camera.imageSize()) {
      away.push_back(f);
      continue;
    }
    cv::Mat resized;
    cv::resize(f, resized, s.camera.imageSize(), 0, 0, cv::INTER_AREA);
    away.push_back(resized);
  }
  // The orders' plans, checked against the frames before the (slow) preparation.
  result.orders = parseFrameOrders(o.orders);
  std::vector<FramePlan> plans;
  for (const FrameOrder& order : result.orders)
    plans.push_back(planFrames(order, result.frames, o.shuffleSeed));

  // The map, as `prepare --input --ref-frames --poses` makes it.
  std::vector<ReferenceImage> images;
  std::vector<RigidPose> poses;
  for (int r : o.references) {
    const RigidPose& T = *s.truth[static_cast<std::size_t>(r)];
    images.push_back(
        {s.frames[static_cast<std::size_t>(r)], "frame " + std::to_string(s.firstFrame + r)});
    poses.push_back(T);
    result.referenceDistancesMm.push_back(1000.0 *
                                          (T.cameraCentre() - poses.front().cameraCentre()).norm());
  }
  // reftrack's map (the Kalman baseline's too); the peers make their own models.
  const bool needsMap = std::any_of(o.methods.begin(), o.methods.end(), [](const std::string& m) {
    return m == "reftrack" || m == "kalman";
  });
  std::optional<MultiPreparation> prepared;
  try {
    if (needsMap)
      prepared = MultiReferencePreparer(s.camera, prepareParams)
                     .prepare(images, poses, "ground truth of bench-real");
  } catch (const Error& e) {
    if (!o.mapFailureIsLoss) throw;
    result.mapError = e.what();
  }
  if (prepared) {
    result.mapPoints = static_cast<int>(prepared->map.points.size());
    for (const ReferenceView& v : prepared->map.views) {
      result.mapKeypoints += static_cast<int>(v.keypoints.keypoints.size());
      result.mapKeypointPoints += v.keypoints.pointCount();
    }
  }

  std::vector<std::unique_ptr<PoseMethod>> methods;
  // Per method: the poses a per-frame peer gave every frame once, replayed in every order.
  std::vector<std::optional<PeerPoses>> replayed;
  for (const std::string& name : groundTruthBenchmarkMethods()) {
    if (std::find(o.methods.begin(), o.methods.end(), name) == o.methods.end()) continue;
    replayed.emplace_back();
    const bool peer = name != "reftrack" && name != "kalman";
    if (peer && o.peerPoses) {
      replayed.back() = o.peerPoses(name, o.references);
      const PeerPoses& poses = *replayed.back();
      if (poses.poses.size() != s.frames.size() || poses.cpuMs.size() != s.frames.size() ||
          poses.reasons.size() != s.frames.size())
        throw Error("bench-real: " + poses.method + " gave " + std::to_string(poses.poses.size()) +
                    " poses for the " + std::to_string(s.frames.size()) + " frames");
      result.modelPoints.emplace_back(poses.method, poses.modelPoints);
      methods.push_back(std::make_unique<NoPoseMethod>(poses.method, "replayed"));
    } else if (!prepared && (name == "reftrack" || name == "kalman")) {
      methods.push_back(std::make_unique<NoPoseMethod>(
          name == "reftrack" ? "reftrack" : "ORB+PnP+Kalman", "no map: " + result.mapError));
    } else if (name == "reftrack") {
      methods.push_back(std::make_unique<ReftrackMethod>(prepared->map, params, result.cube));
    } else if (name == "kalman") {
      auto kalman =
          std::make_unique<KalmanMethod>(prepared->map.pair(0, 1), frameRate(s.timestamps));
      result.modelPoints.emplace_back(kalman->name(), kalman->modelPoints());
      methods.push_back(std::move(kalman));
    } else {
      auto peer = std::make_unique<PeerMethod>(name, s, o.references);
      result.modelPoints.emplace_back(peer->name(), peer->modelPoints());
      methods.push_back(std::move(peer));
    }
  }

  const std::vector<Eigen::Vector3d>& cube = result.cube;
  for (const auto& method : methods)
    for (std::size_t i = 0; i < result.orders.size(); ++i) {
      MethodRun run;
      run.method = method->name();
      run.order = result.orders[i];
      run.plan = plans[i];
      run.errorPx.assign(static_cast<std::size_t>(result.frames), NAN);
      run.poses.resize(static_cast<std::size_t>(result.frames));
      run.predictedErrorPx.assign(static_cast<std::size_t>(result.frames), NAN);
      run.uncertain.assign(static_cast<std::size_t>(result.frames), false);
      result.runs.push_back(std::move(run));
    }
  // The replayed peers: every order from their one run (its CPU times counted once).
  for (std::size_t m = 0; m < methods.size(); ++m)
    for (std::size_t i = 0; replayed[m] && i < result.orders.size(); ++i) {
      MethodRun& run = result.runs[m * result.orders.size() + i];
      replayPeerPoses(*replayed[m], s, cube, run);
      if (progress)
        progress(run.method + ", " + run.order.name + " order: " +
                 std::to_string(run.plan.frames.size()) + " frames replayed from its one run");
    }
  // Each pass runs every method in turn, in every order, so all see the same machine load.
  for (int pass = 0; pass < o.passes; ++pass)
    for (std::size_t m = 0; m < methods.size(); ++m)
      for (std::size_t i = 0; !replayed[m] && i < result.orders.size(); ++i) {
        PoseMethod& method = *methods[m];
        MethodRun& run = result.runs[m * result.orders.size() + i];
        const auto runStart = std::chrono::steady_clock::now();
        playFrames(method, s, cube, pass == 0, run, away);
        if (progress) {
          const double seconds =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - runStart).count();
          char line[256];
          std::snprintf(line, sizeof line, "pass %d/%d: %s, %s order: %zu frames in %.1f s",
                        pass + 1, o.passes, method.name().c_str(), run.order.name.c_str(),
                        run.plan.frames.size(), seconds);
          progress(line);
        }
      }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace reftrack::app
