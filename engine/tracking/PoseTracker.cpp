#include "engine/tracking/PoseTracker.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>
#include <span>
#include <utility>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/estimation/MotionModelFile.hpp"
#include "engine/estimation/RegularizedPoseEstimator.hpp"
#include "engine/estimation/ReprojectionRefiner.hpp"
#include "engine/estimation/RobustScale.hpp"
#include "engine/estimation/RollingShutterEstimator.hpp"
#include "engine/estimation/TemporalRegularizer.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/geometry/FundamentalMatrix.hpp"
#include "engine/matching/DistinctiveCorners.hpp"
#include "engine/matching/NarrowBaselineMatcher.hpp"
#include "engine/matching/PatchAligner.hpp"
#include "engine/tracking/KeypointMeasurer.hpp"
#include "engine/tracking/MeasurementGroupNoise.hpp"
#include "engine/tracking/MeasurementReliability.hpp"
#include "engine/tracking/PoseSupport.hpp"
#include "engine/tracking/PoseVerifier.hpp"
#include "engine/tracking/WideBaselineMatcher.hpp"

namespace reftrack {

const char* toString(TrackingState state) {
  switch (state) {
    case TrackingState::Initialising:
      return "initialising";
    case TrackingState::Tracking:
      return "tracking";
    case TrackingState::Lost:
      return "lost";
  }
  return "unknown";
}

void PoseTrackerLimits::check() const {
  if (minCorners < 4) throw Error("pose tracker: min_corners must be >= 4");
  if (minInliers < 6) throw Error("pose tracker: min_inliers must be >= 6");
  if (!(gatePx > 0) || !std::isfinite(gatePx)) throw Error("pose tracker: gate_px must be > 0");
  if (!(maxRmsPx > 0) || !std::isfinite(maxRmsPx))
    throw Error("pose tracker: max_rms_px must be > 0");
  if (!(maxSigmaTranslation > 0) || !std::isfinite(maxSigmaTranslation))
    throw Error("pose tracker: max_sigma_translation must be > 0");
  if (ransacIterations < 1) throw Error("pose tracker: ransac_iterations must be >= 1");
  if (!(minEpipolarBaseline >= 0) || !std::isfinite(minEpipolarBaseline))
    throw Error("pose tracker: min_epipolar_baseline must be >= 0");
}

namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t).count();
}

Eigen::Vector2d toEigen(cv::Point2f p) { return {p.x, p.y}; }

// One reference image prepared for both matchers, plus its links into the map.
struct PreparedReference {
  MatchableReference matchable;  // distorted pixels, for correlation
  std::vector<Eigen::Vector2d> undistorted;
  // Where each corner's map point was measured (ReferenceMatch::peakA / peakB, undistorted): the
  // correlation peak its 3D point was triangulated from, or the corner itself (no point, no peak).
  // The epipolar terms use it, so that they measure the same scene point as the three-view terms.
  std::vector<Eigen::Vector2d> measured;
  std::vector<cv::Point2f> measuredPixels;  // the same, with lens distortion (for alignment)
  std::vector<float> contrast;
  std::vector<int> mapMatch;  // corner -> index into map.matches, or -1
  std::vector<Corner> asCorners;
  cv::Mat gray;
};

PreparedReference prepare(const cv::Mat& image, const std::vector<ReferenceCorner>& corners,
                          const PinholeCamera& camera, const std::vector<ReferenceMatch>& matches,
                          bool isA) {
  PreparedReference r;
  std::vector<cv::Point2f> pixels;
  for (const ReferenceCorner& c : corners) {
    pixels.push_back(c.pixel);
    r.contrast.push_back(c.rmsContrast);
    r.asCorners.push_back(Corner{c.pixel, 0.0f, c.rmsContrast});
  }
  for (const cv::Point2f& p : camera.undistortPixels(pixels)) r.undistorted.push_back(toEigen(p));
  r.mapMatch.assign(corners.size(), -1);
  r.measured = r.undistorted;
  std::vector<cv::Point2f> peaks;
  std::vector<std::size_t> peakCorners;
  for (int m = 0; m < static_cast<int>(matches.size()); ++m) {
    const ReferenceMatch& match = matches[static_cast<std::size_t>(m)];
    const int c = isA ? match.cornerA : match.cornerB;
    r.mapMatch[static_cast<std::size_t>(c)] = m;
    if (const std::optional<cv::Point2f>& peak = isA ? match.peakA : match.peakB) {
      peaks.push_back(*peak);
      peakCorners.push_back(static_cast<std::size_t>(c));
    }
  }
  const std::vector<cv::Point2f> undistortedPeaks = camera.undistortPixels(peaks);
  r.measuredPixels = pixels;
  for (std::size_t i = 0; i < peakCorners.size(); ++i) {
    r.measured[peakCorners[i]] = toEigen(undistortedPeaks[i]);
    r.measuredPixels[peakCorners[i]] = peaks[i];
  }
  r.gray = toGray8(image);
  // Corners with a 3D point are tried first: they carry the three-view terms.
  std::vector<char> hasPoint(corners.size(), 0);
  for (std::size_t c = 0; c < corners.size(); ++c) hasPoint[c] = r.mapMatch[c] >= 0;
  r.matchable = MatchableReference::build(r.gray, std::move(pixels), hasPoint);
  return r;
}

// Initialisation under a scale hypothesis s: the frame was taken farther from (s > 1) or nearer
// to (s < 1) the scene than the reference, along about the same line of sight. Each frame
// window is resampled at 1/s so that it looks like the reference, and candidates are searched
// around c + s (p - c), c the image centre. Returns (frame corner, reference corner) pairs.
std::vector<CornerMatch> matchAtScale(const NarrowBaselineMatcher& narrow, const cv::Mat& gray,
                                      const std::vector<cv::Point2f>& pixels,
                                      const PreparedReference& ref, double s) {
  const int half = narrow.params().halfWindow;
  const float inv = static_cast<float>(1.0 / s);
  const NccPatches frameWindows = NccPatches::warped(
      gray, pixels, std::vector<cv::Matx22f>(pixels.size(), cv::Matx22f(inv, 0, 0, inv)), half);
  const std::vector<cv::Point2f> refPixels = positionsOf(ref.asCorners);
  const NccPatches refWindows = NccPatches::square(ref.gray, refPixels, half);
  const double cx = (gray.cols - 1) * 0.5, cy = (gray.rows - 1) * 0.5;
  const cv::Matx33d frameToRef(s, 0, cx * (1 - s), 0, s, cy * (1 - s), 0, 0, 1);
  const double r = resolutionScale(gray.size());
  return narrow.match(pixels, frameWindows, refPixels, refWindows,
                      narrow.params().searchHalfWidthPx * r, narrow.params().searchHalfHeightPx * r,
                      frameToRef);
}

// Point-to-epipolar-line distances for a match under F (reference camera -> current camera).
double maxEpipolarDistance(const Eigen::Matrix3d& F, const Eigen::Vector2d& pRef,
                           const Eigen::Vector2d& pK) {
  const Eigen::Vector3d a(pRef.x(), pRef.y(), 1.0), k(pK.x(), pK.y(), 1.0);
  const Eigen::Vector3d lk = F * a, la = F.transpose() * k;
  const double e = k.dot(lk);
  const double dk = std::abs(e) / std::hypot(lk.x(), lk.y());
  const double da = std::abs(e) / std::hypot(la.x(), la.y());
  return std::max(dk, da);
}

// The median image distance (ideal pinhole) between where two poses (reference A -> camera) put
// the three-view terms' map points: how far the scene moved in the image between them.
double medianImageMotion(const PinholeCamera& camera, const RigidPose& before,
                         const RigidPose& after, const PoseMeasurements& m) {
  std::vector<double> moved;
  moved.reserve(m.threeView.size());
  for (const ThreeViewMatch& t : m.threeView) {
    const Eigen::Vector3d a = before * t.pointA, b = after * t.pointA;
    if (a.z() > 1e-6 && b.z() > 1e-6)
      moved.push_back((camera.project(a) - camera.project(b)).norm());
  }
  if (moved.empty()) return 0.0;
  const auto mid = moved.begin() + static_cast<long>(moved.size() / 2);
  std::nth_element(moved.begin(), mid, moved.end());
  return *mid;
}

}  // namespace

struct PoseTracker::Impl {
  ReferenceMap map;
  TrackerParams params;
  PoseTrackerLimits limits;
  CornerVarianceModel varianceModel;
  ArMotionModel motionModel;
  PreparedReference refA, refB;
  std::unique_ptr<CornerDetector> detector;
  std::unique_ptr<RegularizedPoseEstimator> estimator;
  std::unique_ptr<TemporalRegularizer> regularizer;
  // The readout in use when pose.estimate_rolling_shutter is on (shared between the pair
  // trackers of a MultiReferenceTracker: it belongs to the camera, not to a reference pair).
  std::shared_ptr<RollingShutterEstimator> shutter;
  TrackingState state = TrackingState::Initialising;

  // Previous frame: the corners used for frame-to-frame matching and their NCC windows.
  std::vector<cv::Point2f> prevF2F;
  NccPatches prevF2FWindows;
  std::optional<cv::Matx33d> prevFrameToFrame;  // V_{k-1} -> V_{k-2}, when it was measured
  std::vector<PreviousMatch> prevA, prevB;
  // While not tracking, each frame also tries the next of these scale hypotheses (see
  // matchAtScale) when matching at the reference's own scale finds too little.
  static constexpr double kInitScales[] = {2.0, 1.5, 0.6, 0.75, 2.5};
  std::size_t nextInitScale = 0;
  // PoseTracker::seed: the next frame's prediction (world -> camera), consumed by process().
  std::optional<RigidPose> seedPose;
  // The seed's candidates are searched within the tracking window (wide_baseline.dx, dy), not the
  // wide seed search: the seed is this frame's own pose, good to a few pixels (process()).
  bool tightSeed = false;
  // The last tracked frame's T_Ak (reference A -> camera), nullopt after a loss, reset or seed.
  std::optional<RigidPose> lastTAk;

  Impl(ReferenceMap m, const TrackerParams& p, PoseTrackerLimits l)
      : map(std::move(m)), params(p), limits(l) {
    map.check();
    params.check();
    limits.check();
    refA = prepare(map.imageA, map.cornersA, map.camera, map.matches, true);
    refB = prepare(map.imageB, map.cornersB, map.camera, map.matches, false);
    computeDistinctiveCorners();
    computePointCovariances();
    pointReliability =
        MeasurementReliability(map.matches.size(), params.pose.reliabilityPriorObservations);
    cornerReliability = MeasurementReliability(refA.measured.size() + refB.measured.size(),
                                               params.pose.reliabilityPriorObservations);
    estimator = std::make_unique<RegularizedPoseEstimator>(map.camera.K(), map.T_AB());
    applyCornerParams();
    applyPoseParams();
    shutter = std::make_shared<RollingShutterEstimator>(params.pose.rollingShutterReadout);
  }

  // Learned reliability (pose.reliability_prior_observations) of each map point's three-view
  // terms and of each reference corner's epipolar terms (A's corners, then B's). A tracked
  // frame's residuals count once the next frame goes on tracking from it (not seeded, no reset in
  // between): a start its caller refuses teaches nothing.
  MeasurementReliability pointReliability{0, 0.0}, cornerReliability{0, 0.0};
  struct PendingObservation {
    bool point;  // a map point's (else a reference corner's)
    std::size_t source;
    double whitenedSquared;
  };
  std::vector<PendingObservation> pendingReliability;
  // The noise of each kind of term on this camera (pose.group_noise_frames), learned like the
  // reliability: a frame's residuals count once the next frame goes on tracking from it.
  MeasurementGroupNoise groupNoise;
  std::optional<MeasurementGroupNoise::FrameResiduals> pendingGroupResiduals;
  double groupFactor(MeasurementGroup g) const { return groupNoise.varianceFactor(g); }
  std::size_t cornerSource(bool inB, int referenceCorner) const {
    return (inB ? refA.measured.size() : 0) + static_cast<std::size_t>(referenceCorner);
  }

  std::vector<char> distinctiveA, distinctiveB;  // per reference corner (DistinctiveCorners)
  std::unique_ptr<PoseVerifier> verifier;        // the check of every pose (pose.verify_*)
  // The keypoint layer's points measured in every frame (wide_baseline.keypoint_points); their
  // learned reliability follows the map points' (sources map.matches.size() + point index).
  std::unique_ptr<KeypointMeasurer> keypointMeasurer;
  std::vector<PoseTracker::VerificationKeypoint> verificationKeypoints[2];  // in A, in B
  PoseTracker::PoseConfirmation confirmation;  // a second opinion when the check says no
  // Tracked frames since a second opinion kept an unsure pose tracked on, while the track has not
  // been broken (a loss, a seed, a reset); -1: none stands (pose.verify_unsure_every_frames).
  int framesSinceOpinion = -1;
  // Repeated texture within reach of a start's search (the narrow-baseline window, the seed
  // search) can fool a start by a whole period; a look-alike correlating above the matcher's
  // acceptance there makes a corner repeated. Not the whole image: generic corners (an L, a
  // T-junction) find a look-alike somewhere in most images (the simulator's scenes kept 1-2
  // distinctive corners that way). Nor enough alone: starts two chessboard squares off on the real
  // desk clip kept 13-18 such corners (8-10 with look-alikes sought in the whole image); the
  // keypoint check of MultiReferenceTracker's verification refuses them
  // (relocalisation.min_keypoint_support).
  void computeDistinctiveCorners() {
    const double radius = distinctiveRadius();
    const int half = params.correlation.halfWindow;
    const double twin = params.correlation.minScore;
    distinctiveA = distinctiveCorners(refA.gray, refA.matchable.corners, half, radius, twin);
    distinctiveB = distinctiveCorners(refB.gray, refB.matchable.corners, half, radius, twin);
    buildVerifier();
  }
  double distinctiveRadius() const {
    return 1.5 * resolutionScale(map.camera.imageSize()) *
           std::max({params.correlation.searchHalfWidthPx, params.correlation.searchHalfHeightPx,
                     static_cast<double>(params.wideBaseline.seedSearchAt320x240)});
  }

  // The verifier reads the map points where the references measured them, each flagged with its
  // corner's distinctiveness in that reference, and the references' keypoints with a 3D point
  // (setVerificationKeypoints), flagged alike.
  void buildVerifier() {
    const double radius = distinctiveRadius();
    std::vector<Eigen::Vector3d> points;
    VerifiedReference a, b;
    a.gray8 = refA.matchable.gray8;
    b.gray8 = refB.matchable.gray8;
    for (const ReferenceMatch& m : map.matches) {
      const auto ca = static_cast<std::size_t>(m.cornerA), cb = static_cast<std::size_t>(m.cornerB);
      points.push_back(m.pointA);
      a.pixels.push_back(refA.measuredPixels[ca]);
      a.distinctive.push_back(distinctiveA[ca]);
      b.pixels.push_back(refB.measuredPixels[cb]);
      b.distinctive.push_back(distinctiveB[cb]);
    }
    const cv::Point2f none(NAN, NAN);
    for (int r = 0; r < 2; ++r) {
      VerifiedReference& seen = r == 0 ? a : b;
      VerifiedReference& other = r == 0 ? b : a;
      std::vector<cv::Point2f> pixels;
      for (const PoseTracker::VerificationKeypoint& k : verificationKeypoints[r]) {
        points.push_back(map.T_A * k.world);
        pixels.push_back(k.pixel);
        seen.pixels.push_back(k.pixel);
        other.pixels.push_back(none);
        other.distinctive.push_back(0);
      }
      const std::vector<char> distinctive = distinctiveCorners(
          seen.gray8, pixels, params.correlation.halfWindow, radius, params.correlation.minScore);
      seen.distinctive.insert(seen.distinctive.end(), distinctive.begin(), distinctive.end());
    }
    verifier = std::make_unique<PoseVerifier>(map.camera, std::move(points), map.T_AB(),
                                              std::move(a), std::move(b), verifierParams());
    buildKeypointMeasurer();
  }
  void buildKeypointMeasurer() {
    std::vector<MeasurableKeypoint> keypoints;
    for (int r = 0; r < 2; ++r)
      for (const PoseTracker::VerificationKeypoint& k : verificationKeypoints[r])
        keypoints.push_back({map.T_A * k.world, k.pixel, r});
    // Ten steps down to 0.02 px: the start is the linear pose's projection, a pixel or so off;
    // measured on both real clips (four orders each), the same cube errors within 0.002 px as 40
    // steps down to 0.005 px (the aligner's defaults).
    PatchAlignerParams ap;
    ap.halfWindow = params.wideBaseline.keypointHalfWindow;
    ap.maxIterations = 10;
    ap.epsilonPx = 0.02;
    keypointMeasurer = std::make_unique<KeypointMeasurer>(
        map.camera, std::move(keypoints), refA.matchable.gray8, refB.matchable.gray8, ap);
    // A point whose window the other reference does not confirm is mostly one no frame confirms
    // (desk: 225 of 408 dropped, they aligned in < 10% of frames and took 56% of the alignments);
    // dropping them: desk CPU per frame x1.18 faster, desk p95 0.658 -> 0.603 px, Kinect pairs
    // within 5 px 120 -> 140 (research README, "Points the other reference does not confirm").
    keypointMeasurer->dropPointsFailingBetweenReferences(map.T_AB());
    pointReliability.resize(map.matches.size() + keypointMeasurer->points().size());
  }
  PoseVerifierParams verifierParams() const {
    PoseVerifierParams p;
    p.halfWindow = params.wideBaseline.halfWindow;
    p.minScore = params.wideBaseline.minScore;
    p.minConfirmed = params.pose.verifyMinPoints;
    p.minConfirmedShare = params.pose.verifyMinShare;
    p.minUnsure = params.pose.verifyUnsurePoints;
    p.minUnsureShare = params.pose.verifyUnsureShare;
    return p;
  }

  // Each map point's covariance (camera A's frame) from its two-reference triangulation: the
  // information of A's and B's measurements, each with the variance the corner-variance model
  // gives its corner (the frame's corners are weighted by the same model), times
  // pose.map_point_sd_scale squared.
  std::vector<Eigen::Matrix3d> pointCovariance;
  static Eigen::Matrix<double, 2, 3> projectionJacobian(const Eigen::Matrix3d& K,
                                                        const Eigen::Vector3d& X) {
    Eigen::Matrix<double, 2, 3> J;
    const double iz = 1.0 / X.z();
    J << K(0, 0) * iz, K(0, 1) * iz, -(K(0, 0) * X.x() + K(0, 1) * X.y()) * iz * iz, 0.0,
        K(1, 1) * iz, -K(1, 1) * X.y() * iz * iz;
    return J;
  }
  void computePointCovariances() {
    const Eigen::Matrix3d& K = map.camera.K();
    const RigidPose TAB = map.T_AB();
    pointCovariance.clear();
    for (const ReferenceMatch& m : map.matches) {
      const Eigen::Matrix<double, 2, 3> JA = projectionJacobian(K, m.pointA);
      const Eigen::Matrix<double, 2, 3> JB = projectionJacobian(K, TAB * m.pointA) * TAB.rotation();
      const double vA = varianceModel.variance(refA.contrast[static_cast<std::size_t>(m.cornerA)]);
      const double vB = varianceModel.variance(refB.contrast[static_cast<std::size_t>(m.cornerB)]);
      const Eigen::Matrix3d information = JA.transpose() * JA / vA + JB.transpose() * JB / vB;
      const double scale = params.pose.mapPointSdScale;
      pointCovariance.push_back(information.inverse() * (scale * scale));
    }
  }

  // A keypoint point's covariance as computePointCovariances gives a map point's, its two
  // reference pixels taken as measured to wide_baseline.keypoint_sigma_px.
  Eigen::Matrix3d keypointCovariance(const Eigen::Vector3d& pointA) const {
    const Eigen::Matrix3d& K = map.camera.K();
    const RigidPose TAB = map.T_AB();
    const Eigen::Matrix<double, 2, 3> JA = projectionJacobian(K, pointA);
    const Eigen::Matrix<double, 2, 3> JB = projectionJacobian(K, TAB * pointA) * TAB.rotation();
    const double sd = params.pose.mapPointSdScale * params.wideBaseline.keypointSigmaPx;
    return (JA.transpose() * JA + JB.transpose() * JB).inverse() * (sd * sd);
  }

  // The whitening of a three-view residual: its covariance is the frame pixel's sigma^2 I plus the
  // point's covariance seen from the frame (J Sigma_P J^T, J at the pose T_Ak).
  Eigen::Matrix2d threeViewWhitening(const RigidPose& TAk, int mapMatch, double sigma) const {
    const auto m = static_cast<std::size_t>(mapMatch);
    return threeViewWhitening(TAk, map.matches[m].pointA, pointCovariance[m], sigma);
  }
  Eigen::Matrix2d threeViewWhitening(const RigidPose& TAk, const Eigen::Vector3d& pointA,
                                     const Eigen::Matrix3d& covariance, double sigma) const {
    const Eigen::Vector3d X = TAk * pointA;
    const Eigen::Matrix<double, 2, 3> J = projectionJacobian(map.camera.K(), X) * TAk.rotation();
    const Eigen::Matrix2d C =
        sigma * sigma * Eigen::Matrix2d::Identity() + J * covariance * J.transpose();
    const Eigen::Matrix2d L = C.llt().matrixL();
    return L.inverse();
  }

  double readout() const {
    return params.pose.estimateRollingShutter ? shutter->readout()
                                              : params.pose.rollingShutterReadout;
  }

  // The frame's corner detector (kept across frames: it adapts its threshold to the sequence).
  void applyCornerParams() {
    // Full-resolution detection: the pyramid shortcut is faster but its corners repeat across
    // viewpoints far less often (measured: 75% vs 23% of corners within 0.5 px under a small
    // warp), and wide-baseline matching lives on repeatable corners.
    CornerParams cornerParams = params.corners;
    cornerParams.detectAtPaperScale = false;
    // The paper's 50-60 corners per 320x240 frame serve one homography; six degrees of freedom
    // against two references need more support: at least twice that (measured at 320x240: 55
    // corners left ~15 3D-2D inliers and lost half the frames of a hand-held sequence).
    cornerParams.countAt320x240 = std::max(cornerParams.countAt320x240, 2 * 55);
    cornerParams.quality = std::min(cornerParams.quality, params.wideBaseline.frameCornerQuality);
    // A map made from denser corners (soft images repeat few of the strongest corners between
    // views) has its points on corners this detector would not find: frames are detected at
    // least as densely. Kinect pair 440/460 (233 points, from 4000 corners per reference): the
    // reference frame itself found 14 of them, "too few 3D-2D matches", and 0 of frames 420-499
    // were tracked; detected like the map, 11 (app/research/README.md, "Maps from soft images").
    if (map.denserCorners) {
      cornerParams.countAt320x240 =
          std::max(cornerParams.countAt320x240, map.denserCorners->countAt320x240);
      cornerParams.quality = std::min(cornerParams.quality, map.denserCorners->quality);
      cornerParams.minDistancePx =
          std::min(cornerParams.minDistancePx, map.denserCorners->minDistancePx);
    }
    detector = std::make_unique<CornerDetector>(cornerParams);
  }

  void applyPoseParams() {
    groupNoise.setFrames(params.pose.groupNoiseFrames);
    if (!params.pose.motionModelFile.empty()) {
      // A fitted model (`reftrack fit-motion`) replaces the AR order and Q of the parameters.
      motionModel = loadMotionModel(params.pose.motionModelFile).model;
    } else {
      std::vector<Vector6d> weights(static_cast<std::size_t>(params.pose.arOrder),
                                    Vector6d::Zero());
      weights[0] = Vector6d::Ones();  // AR(p) default: x_pred = x_{k-1}
      motionModel = ArMotionModel(
          weights,
          ArMotionModel::diagonalNoise(params.pose.translationSigma, params.pose.rotationSigma));
    }
    regularizer = std::make_unique<TemporalRegularizer>(motionModel, params.pose.estimator,
                                                        params.pose.alpha);
  }

  void lose(PoseTrackingResult& r, const std::string& why) {
    r.state = TrackingState::Lost;
    r.message = why;
    r.worldToCamera.reset();
    r.T_Ak.reset();
    state = TrackingState::Lost;
    lastTAk.reset();
    framesSinceOpinion = -1;
    regularizer->reset();
    prevA.clear();
    prevB.clear();
    prevFrameToFrame.reset();
  }

  // The same frame again, seeded by its own pose T_Ak and matched within the tracking window
  // (tightSeed); its result is the frame's. `firstPass` names the pass before it in the timings.
  PoseTrackingResult matchAgainAround(const cv::Mat& frame, const RigidPose& TAk,
                                      const char* firstPass, Clock::time_point start) {
    seedWith(TAk * map.T_A, true);
    const double firstPassMs = msSince(start);
    PoseTrackingResult again = process(frame);
    again.timings.insert(
        again.timings.begin(),
        {std::string("before the match around the pose (") + firstPass + ")", firstPassMs});
    return again;
  }

  // The next process() starts from this world -> camera pose (PoseTracker::seed), its candidates
  // searched within the tracking window when `tight`, else the wide seed search.
  void seedWith(const RigidPose& worldToCamera, bool tight) {
    seedPose = worldToCamera;
    tightSeed = tight;
    lastTAk.reset();
    framesSinceOpinion = -1;
    regularizer->reset();
  }

  // Previous-match seeds from a predicted pose: every map point in front of the camera and
  // projecting near the frame (within half its size outside it: neighbours for the local affine
  // maps of corners near the border), paired with its corner in A and in B.
  void seedsFromPose(const RigidPose& worldToCamera, cv::Size size) {
    prevA.clear();
    prevB.clear();
    const RigidPose TAk = worldToCamera * map.T_A.inverse();
    const double mx = 0.5 * size.width, my = 0.5 * size.height;
    for (const ReferenceMatch& m : map.matches) {
      const Eigen::Vector3d X = TAk * m.pointA;
      if (!(X.z() > 1e-6)) continue;
      const Eigen::Vector2d p = map.camera.projectDistorted(X);
      if (!(p.x() > -mx && p.y() > -my && p.x() < size.width + mx && p.y() < size.height + my))
        continue;
      const cv::Point2f pixel(static_cast<float>(p.x()), static_cast<float>(p.y()));
      prevA.push_back({pixel, m.cornerA});
      prevB.push_back({pixel, m.cornerB});
    }
  }

  // The stages of process() and what passes between them.
  struct FrameCorners {
    std::vector<Corner> corners;
    std::vector<cv::Point2f> pixels;
    std::vector<cv::Point2f> f2fPoints;  // the strongest, for the next frame-to-frame matching
    NccPatches f2fWindows;
  };
  struct FrameMatches {
    std::vector<WideBaselineMatch> toA, toB;  // frame corner -> reference corner
    cv::Matx33d H = cv::Matx33d::eye();       // V_k -> V_{k-1} (identity unless measured)
    bool haveFrameToFrame = false;
  };
  struct Measurements {
    std::vector<Eigen::Vector2d> undistorted;      // corrected, undistorted frame pixels
    std::vector<std::size_t> toA, toB;             // per match: its index in `undistorted`
    std::vector<Eigen::Vector2d> shiftPerReadout;  // per measurement (readout estimate only)
    double readout = 0.0;                          // the rolling-shutter readout applied
  };
  struct Pair3D {
    int frameCorner, mapMatch;
    std::size_t measurement;  // index into Measurements::undistorted
  };
  struct Inliers {
    Vector6d xLin = Vector6d::Zero();  // the robust linear pose (PnP-RANSAC, refined)
    PoseMeasurements measurements;     // the gated terms for the estimator
    std::vector<char> inlierA, inlierB;
    std::vector<std::size_t> threeViewMeasurement;      // per three-view term: its measurement
    std::vector<int> threeViewMapMatch;                 // per three-view term: its map match
    std::vector<int> epipolarCornerA, epipolarCornerB;  // per epipolar term: its reference corner
    std::vector<std::size_t> epipolarMatchA, epipolarMatchB;  // ... and its match (m.toA, m.toB)
    int distinctive = 0;  // gated matches to distinctive reference corners
  };
  FrameCorners detectCorners(const cv::Mat& gray);
  void matchFrameToFrame(const FrameCorners& c, double scale, FrameMatches& m);
  void matchWideBaseline(const MatchableFrame& matchable, bool wideSeed, FrameMatches& m,
                         PoseTrackingResult& r, const MapsToPrevious* mapsA = nullptr,
                         const MapsToPrevious* mapsB = nullptr);
  bool verifyPose(const cv::Mat& frame, const cv::Mat& gray, const RigidPose& TAk, bool trackedOn,
                  PoseTrackingResult& r);
  void matchInitial(const cv::Mat& gray, const FrameCorners& c, FrameMatches& m);
  void completeThroughMap(std::size_t frameCorners, FrameMatches& m) const;
  Measurements measure(const cv::Mat& gray, const FrameCorners& c, const FrameMatches& m);
  std::vector<Pair3D> threeViewPairs(const FrameMatches& m, const Measurements& meas) const;
  std::optional<Inliers> rejectOutliers(const FrameCorners& c, const FrameMatches& m,
                                        const Measurements& meas, const std::vector<Pair3D>& pairs,
                                        double gate, PoseTrackingResult& r);
  void measureKeypoints(const cv::Mat& gray, double gate, Inliers& in, PoseTrackingResult& r);
  std::optional<std::string> supportFailure(const PoseEstimate& est, const PoseMeasurements& meas,
                                            std::size_t supportTerms, double scale,
                                            PoseTrackingResult& r) const;
  void keepInliers(const FrameCorners& c, const FrameMatches& m, const Inliers& in,
                   PoseTrackingResult& r);
  void recordResiduals(const RigidPose& TAk, const Inliers& in);
  // Each term's squared residual at TAk, whitened as weighted (every factor in): the three-view
  // terms' 2-D norms, the epipolar terms' distance to the line (to A, to B).
  struct TermResiduals {
    std::vector<double> threeView, toA, toB;
  };
  TermResiduals whitenedResiduals(const RigidPose& TAk, const PoseMeasurements& pm) const;
  int dropOutlierTerms(const RigidPose& TAk, Inliers& in) const;
  PoseTrackingResult process(const cv::Mat& frame);
};

// ---- The per-frame stages. Each takes what it needs and fills its own output; process() reads
// top to bottom as the paper's pipeline.

// Stage 1, corners: the frame's corners, and the strongest of them (with their NCC windows) for
// the next frame's frame-to-frame matching.
PoseTracker::Impl::FrameCorners PoseTracker::Impl::detectCorners(const cv::Mat& gray) {
  FrameCorners c;
  c.corners = detector->detect(gray);
  c.pixels = positionsOf(c.corners);
  // Frame-to-frame matching only predicts W = L H (Eq. 18): the strongest corners suffice.
  const std::size_t f2fCount = std::min<std::size_t>(
      c.pixels.size(),
      static_cast<std::size_t>(params.wideBaseline.frameToFrameCornersFor(gray.size())));
  c.f2fPoints.assign(c.pixels.begin(), c.pixels.begin() + static_cast<long>(f2fCount));
  c.f2fWindows = NccPatches::square(gray, c.f2fPoints, params.correlation.halfWindow);
  return c;
}

// Stage 2, frame to frame (tracked frames): the homography V_k -> V_{k-1} from narrow-baseline
// matches of the strongest corners. Only a prediction for W = L H (Eq. 18), so OpenCV's RANSAC
// homography suffices; a failure leaves the identity.
void PoseTracker::Impl::matchFrameToFrame(const FrameCorners& c, double scale, FrameMatches& m) {
  const NarrowBaselineMatcher narrow(params.correlation);
  const std::vector<CornerMatch> f2f = narrow.match(
      c.f2fPoints, c.f2fWindows, prevF2F, prevF2FWindows,
      params.correlation.searchHalfWidthPx * scale, params.correlation.searchHalfHeightPx * scale);
  if (f2f.size() < 8) return;
  std::vector<cv::Point2f> a, b;
  for (const CornerMatch& x : f2f) {
    a.push_back(c.f2fPoints[static_cast<std::size_t>(x.first)]);
    b.push_back(prevF2F[static_cast<std::size_t>(x.second)]);
  }
  const cv::Mat Hm = cv::findHomography(a, b, cv::RANSAC, 3.0 * scale);
  if (Hm.empty()) return;
  m.H = cv::Matx33d(Hm);
  m.haveFrameToFrame = true;
}

// Stage 3a, wide-baseline matching (tracked or seeded frames): the frame's corners to V_A and
// V_B through W = L H (Eq. 18-19), from the previous frame's matches (or the seed's projections,
// H = identity, candidates within wide_baseline.seed_search).
void PoseTracker::Impl::matchWideBaseline(const MatchableFrame& matchable, bool wideSeed,
                                          FrameMatches& m, PoseTrackingResult& r,
                                          const MapsToPrevious* mapsA,
                                          const MapsToPrevious* mapsB) {
  WideBaselineParams wideParams = params.wideBaseline;
  if (wideSeed) wideParams.dx = wideParams.dy = wideParams.seedSearchAt320x240;
  const WideBaselineMatcher wide(wideParams);
  // V_A and V_B are matched at once, one task each on OpenCV's threads (one thread: in turn).
  // Each reads the frame's windows and its own reference and writes its own matches, so the
  // matches are the same on any number of threads; a frame's wall clock loses the shorter of
  // the two (desk clip, 752x480: ~0.16 ms of ~2.2; research README, "Two cores for a frame").
  double msA = 0.0, msB = 0.0;
  cv::parallel_for_(cv::Range(0, 2), [&](const cv::Range& range) {
    for (int task = range.start; task < range.end; ++task) {
      const Clock::time_point began = Clock::now();
      if (task == 0) {
        m.toA = wide.match(matchable, m.H, prevA, refA.matchable, mapsA);
        msA = msSince(began);
      } else {
        m.toB = wide.match(matchable, m.H, prevB, refB.matchable, mapsB);
        msB = msSince(began);
      }
    }
  });
  r.timings.push_back({"match A", msA});
  r.timings.push_back({"match B", msB});
}

// Stage 3b, initialisation (paper Sec. 6.2): narrow-baseline matching to V_A and V_B; when that
// finds too little, one of a few distance ratios per frame (matchAtScale: a start from farther
// away or nearer than the reference, along about its line of sight).
void PoseTracker::Impl::matchInitial(const cv::Mat& gray, const FrameCorners& c, FrameMatches& m) {
  const NarrowBaselineMatcher narrow(params.correlation);
  std::vector<CornerMatch> nA = narrow.match(gray, c.corners, refA.gray, refA.asCorners);
  std::vector<CornerMatch> nB = narrow.match(gray, c.corners, refB.gray, refB.asCorners);
  double s = 1.0;
  if (nA.size() + nB.size() < static_cast<std::size_t>(4 * limits.minInliers)) {
    const double scaleHypothesis = kInitScales[nextInitScale++ % std::size(kInitScales)];
    std::vector<CornerMatch> sA = matchAtScale(narrow, gray, c.pixels, refA, scaleHypothesis);
    std::vector<CornerMatch> sB = matchAtScale(narrow, gray, c.pixels, refB, scaleHypothesis);
    if (sA.size() + sB.size() > nA.size() + nB.size()) {
      nA = std::move(sA);
      nB = std::move(sB);
      s = scaleHypothesis;
    }
  }
  // The frame windows were compared with the reference's at scale s: frame offsets map to
  // reference offsets by s I (for the frame-side alignment).
  const cv::Matx22d J(s, 0, 0, s);
  for (const CornerMatch& x : nA) m.toA.push_back({x.first, x.second, x.score, {}, J});
  for (const CornerMatch& x : nB) m.toB.push_back({x.first, x.second, x.score, {}, J});
}

// Stage 4, matches implied through the map's A<->B matches complete the other side: a frame
// corner matched to a corner of A with a map point is matched to that point's corner of B too
// (and vice versa), unless either already has a match there.
void PoseTracker::Impl::completeThroughMap(std::size_t frameCorners, FrameMatches& m) const {
  std::vector<int> frameToB(frameCorners, -1), frameToA(frameCorners, -1);
  for (const WideBaselineMatch& x : m.toB)
    frameToB[static_cast<std::size_t>(x.frameCorner)] = x.referenceCorner;
  for (const WideBaselineMatch& x : m.toA)
    frameToA[static_cast<std::size_t>(x.frameCorner)] = x.referenceCorner;
  std::vector<char> usedB(refB.undistorted.size(), 0), usedA(refA.undistorted.size(), 0);
  for (const WideBaselineMatch& x : m.toB) usedB[static_cast<std::size_t>(x.referenceCorner)] = 1;
  for (const WideBaselineMatch& x : m.toA) usedA[static_cast<std::size_t>(x.referenceCorner)] = 1;
  const std::size_t nA0 = m.toA.size(), nB0 = m.toB.size();
  for (std::size_t i = 0; i < nA0; ++i) {
    const int mm = refA.mapMatch[static_cast<std::size_t>(m.toA[i].referenceCorner)];
    if (mm < 0) continue;
    const int b = map.matches[static_cast<std::size_t>(mm)].cornerB;
    if (frameToB[static_cast<std::size_t>(m.toA[i].frameCorner)] < 0 &&
        !usedB[static_cast<std::size_t>(b)]) {
      m.toB.push_back({m.toA[i].frameCorner, b, m.toA[i].score, {}, {}});
      usedB[static_cast<std::size_t>(b)] = 1;
    }
  }
  for (std::size_t i = 0; i < nB0; ++i) {
    const int mm = refB.mapMatch[static_cast<std::size_t>(m.toB[i].referenceCorner)];
    if (mm < 0) continue;
    const int a = map.matches[static_cast<std::size_t>(mm)].cornerA;
    if (frameToA[static_cast<std::size_t>(m.toB[i].frameCorner)] < 0 &&
        !usedA[static_cast<std::size_t>(a)]) {
      m.toA.push_back({m.toB[i].frameCorner, a, m.toB[i].score, {}, {}});
      usedA[static_cast<std::size_t>(a)] = 1;
    }
  }
}

// Stage 5, measurements: one frame pixel per match (the frame corner, or where the reference's
// measured point aligns: wide_baseline.align_frame_side), corrected for the rolling shutter
// (pose.rolling_shutter_readout, or its online estimate) and undistorted.
PoseTracker::Impl::Measurements PoseTracker::Impl::measure(const cv::Mat& gray,
                                                           const FrameCorners& c,
                                                           const FrameMatches& m) {
  Measurements out;
  out.toA.resize(m.toA.size());
  out.toB.resize(m.toB.size());
  std::vector<cv::Point2f> pixels;
  pixels.reserve(m.toA.size() + m.toB.size());
  const PatchAligner aligner = [&] {
    PatchAlignerParams ap;
    ap.halfWindow = params.wideBaseline.alignHalfWindow;
    return PatchAligner(ap);
  }();
  const auto collect = [&](const std::vector<WideBaselineMatch>& ms, const PreparedReference& ref,
                           std::vector<std::size_t>& index) {
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const WideBaselineMatch& x = ms[i];
      const cv::Point2f corner = c.pixels[static_cast<std::size_t>(x.frameCorner)];
      std::optional<PatchAlignment> aligned;
      if (params.wideBaseline.alignFrameSide && x.frameToReference)
        aligned =
            aligner.align(ref.gray, ref.measuredPixels[static_cast<std::size_t>(x.referenceCorner)],
                          *x.frameToReference, gray, corner);
      index[i] = pixels.size();
      pixels.push_back(aligned ? aligned->position : corner);
    }
  };
  collect(m.toA, refA, out.toA);
  collect(m.toB, refB, out.toB);

  const double readoutUsed = readout();
  out.readout = readoutUsed;
  // Rolling shutter: row y was exposed (y - c) / (rows - 1) readouts after the middle row c; the
  // measurement moves back along its image velocity (pixels per frame interval) by that fraction
  // of it. Matching keeps the observed pixels.
  const bool estimating = params.pose.estimateRollingShutter && m.haveFrameToFrame;
  std::vector<cv::Point2f> corrected = pixels, unitShifted;
  if ((readoutUsed > 0 || estimating) && m.haveFrameToFrame) {
    const double middle = 0.5 * (gray.rows - 1);
    if (estimating) unitShifted = pixels;
    for (std::size_t i = 0; i < corrected.size(); ++i) {
      cv::Point2f& p = corrected[i];
      const cv::Vec3d q = m.H * cv::Vec3d(p.x, p.y, 1.0);
      if (!(std::abs(q[2]) > 1e-12)) continue;
      const double f = (p.y - middle) / (gray.rows - 1);
      // The image velocity at the middle row's instant: H gives it half a frame earlier, and the
      // previous frame's homography one and a half; extrapolated linearly (hand-held motion
      // accelerates: measured at 1280x720, webcam effects, readout known, cube error mean
      // 0.353 px with the backward difference alone, 0.267 px extrapolated).
      double vx = p.x - q[0] / q[2], vy = p.y - q[1] / q[2];
      if (prevFrameToFrame) {
        const cv::Vec3d q2 = (*prevFrameToFrame) * q;
        if (std::abs(q2[2]) > 1e-12) {
          const double ux = q[0] / q[2] - q2[0] / q2[2], uy = q[1] / q[2] - q2[1] / q2[2];
          vx = 1.5 * vx - 0.5 * ux;
          vy = 1.5 * vy - 0.5 * uy;
        }
      }
      const double dx = f * vx, dy = f * vy;
      if (estimating) unitShifted[i] -= cv::Point2f(static_cast<float>(dx), static_cast<float>(dy));
      p.x -= static_cast<float>(readoutUsed * dx);
      p.y -= static_cast<float>(readoutUsed * dy);
    }
  }
  for (const cv::Point2f& p : map.camera.undistortPixels(corrected))
    out.undistorted.push_back(toEigen(p));
  prevFrameToFrame = m.haveFrameToFrame ? std::optional<cv::Matx33d>(m.H) : std::nullopt;
  if (estimating) {
    // How far each undistorted measurement moves per unit of readout (the readout's estimate).
    const std::vector<cv::Point2f> raw = map.camera.undistortPixels(pixels);
    const std::vector<cv::Point2f> moved = map.camera.undistortPixels(unitShifted);
    for (std::size_t i = 0; i < raw.size(); ++i)
      out.shiftPerReadout.push_back(toEigen(raw[i]) - toEigen(moved[i]));
  }
  return out;
}

// Stage 6, three-view pairs: the frame measurements of map points (seen through A, else B),
// each map point once.
std::vector<PoseTracker::Impl::Pair3D> PoseTracker::Impl::threeViewPairs(
    const FrameMatches& m, const Measurements& meas) const {
  std::vector<Pair3D> pairs;
  std::vector<char> usedMap(map.matches.size(), 0);
  const auto add = [&](const std::vector<WideBaselineMatch>& ms, const PreparedReference& ref,
                       const std::vector<std::size_t>& measurement) {
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const int mm = ref.mapMatch[static_cast<std::size_t>(ms[i].referenceCorner)];
      if (mm < 0 || usedMap[static_cast<std::size_t>(mm)]) continue;
      usedMap[static_cast<std::size_t>(mm)] = 1;
      pairs.push_back({ms[i].frameCorner, mm, measurement[i]});
    }
  };
  add(m.toA, refA, meas.toA);
  add(m.toB, refB, meas.toB);
  return pairs;
}

// Stage 7, outlier rejection: PnP-RANSAC on the 3D-2D pairs gives a robust linear pose; the
// matches within the gate under it (epipolar distance for every match, reprojection for the
// pairs) enter the estimator, weighted by their corners' variances (and the map points' own
// uncertainty: pose.map_point_sd_scale). nullopt (with the reason in r) when too few remain.
std::optional<PoseTracker::Impl::Inliers> PoseTracker::Impl::rejectOutliers(
    const FrameCorners& c, const FrameMatches& m, const Measurements& meas,
    const std::vector<Pair3D>& pairs, double gate, PoseTrackingResult& r) {
  if (static_cast<int>(pairs.size()) < limits.minInliers) {
    lose(r, "too few 3D-2D matches (" + std::to_string(pairs.size()) + ")");
    return std::nullopt;
  }
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const Pair3D& p : pairs) {
    const Eigen::Vector3d& P = map.matches[static_cast<std::size_t>(p.mapMatch)].pointA;
    object.emplace_back(P.x(), P.y(), P.z());
    const Eigen::Vector2d& q = meas.undistorted[p.measurement];
    image.emplace_back(q.x(), q.y());
  }
  cv::Vec3d rvec, tvec;
  std::vector<int> ransacInliers;
  const cv::Matx33d Kcv = map.camera.Kcv();
  const bool ok = cv::solvePnPRansac(object, image, Kcv, cv::noArray(), rvec, tvec, false,
                                     limits.ransacIterations, static_cast<float>(gate), 0.999,
                                     ransacInliers, cv::SOLVEPNP_AP3P);
  if (!ok || static_cast<int>(ransacInliers.size()) < limits.minInliers) {
    lose(r, "PnP-RANSAC found no pose with enough support (" +
                std::to_string(ransacInliers.size()) + " inliers)");
    return std::nullopt;
  }
  {
    std::vector<cv::Point3d> o;
    std::vector<cv::Point2d> im;
    for (int i : ransacInliers) {
      o.push_back(object[static_cast<std::size_t>(i)]);
      im.push_back(image[static_cast<std::size_t>(i)]);
    }
    // OpenCV re-fits the pose of a P3P/AP3P RANSAC on its inliers with EPnP, which can fail on
    // a planar scene seen almost as a reference saw it (measured on the plane tests: all 73
    // inliers of the best model, a returned pose 40 degrees off that none of them fits). SQPnP
    // is globally optimal for any point configuration; the fit that reprojects the inliers
    // better is refined.
    auto inlierRms = [&](const cv::Vec3d& rv, const cv::Vec3d& tv) {
      std::vector<cv::Point2d> back;
      cv::projectPoints(o, rv, tv, Kcv, cv::noArray(), back);
      double sum = 0.0;
      for (std::size_t i = 0; i < back.size(); ++i) sum += std::pow(cv::norm(back[i] - im[i]), 2);
      return std::sqrt(sum / static_cast<double>(back.size()));
    };
    cv::Vec3d rSq, tSq;
    if (cv::solvePnP(o, im, Kcv, cv::noArray(), rSq, tSq, false, cv::SOLVEPNP_SQPNP) &&
        inlierRms(rSq, tSq) < inlierRms(rvec, tvec)) {
      rvec = rSq;
      tvec = tSq;
    }
    // ReprojectionRefiner, not cv::solvePnPRefineLM: the same minimum, and OpenCV's LM was
    // 0.15 ms of the desk clip's 2.4 ms frame.
    refineReprojection(o, im, Kcv, rvec, tvec);
  }
  // The pairs gated again at their own robust scale (pose.outlier_gate_sigmas), the linear pose
  // refitted to those within, twice (the gate tightened in between): the wide gate lets in wrong
  // matches a few pixels off that pull the refit by a pixel or more (the ViSP clip's frames 10, 28,
  // 32: one or two matches 18-40 px off the true pose).
  if (params.pose.outlierGateSigmas > 0) {
    const double floorPx = params.pose.minOutlierGatePx * gate / limits.gatePx;
    const double wideGate = gate;
    std::vector<cv::Point2d> back;
    std::vector<double> residual, within;
    for (int pass = 0; pass < 2; ++pass) {
      cv::projectPoints(object, rvec, tvec, Kcv, cv::noArray(), back);
      residual.clear();
      within.clear();
      for (std::size_t i = 0; i < back.size(); ++i) {
        residual.push_back(cv::norm(back[i] - image[i]));
        if (residual.back() <= gate) within.push_back(residual.back());
      }
      if (static_cast<int>(within.size()) < limits.minInliers) break;
      const double tight = std::clamp(
          params.pose.outlierGateSigmas * robustSd(within, ResidualDimension::Two), floorPx, gate);
      std::vector<cv::Point3d> o;
      std::vector<cv::Point2d> im;
      for (std::size_t i = 0; i < residual.size(); ++i)
        if (residual[i] <= tight) {
          o.push_back(object[i]);
          im.push_back(image[i]);
        }
      if (static_cast<int>(o.size()) < limits.minInliers) break;
      refineReprojection(o, im, Kcv, rvec, tvec);
      gate = tight;
    }
    // Only the refit uses the tight gate: the terms below keep the wide one. Dropping their
    // pairs too cost the desk clip 0.344 -> 0.398 px (a sharp camera's good pairs at the edge of
    // the lens model look like outliers), whereas the refit alone keeps it at 0.346 and still
    // takes the ViSP clip 0.634 -> 0.510 (app/research/README.md).
    gate = wideGate;
  }
  Inliers in;
  in.xLin << tvec[0], tvec[1], tvec[2], rvec[0], rvec[1], rvec[2];
  const RigidPose TAkLin = RigidPose::fromVector6(in.xLin);
  // Near a reference camera the epipolar geometry degenerates (F -> 0 as the baseline vanishes,
  // and the distance's derivatives blow up): below minEpipolarBaseline its terms are left out and
  // the three-view terms carry the pose. The gate still uses them to reject outliers.
  const RigidPose TBkLin = TAkLin * map.T_AB().inverse();
  const bool useEpipolarA = TAkLin.translation().norm() >= limits.minEpipolarBaseline;
  const bool useEpipolarB = TBkLin.translation().norm() >= limits.minEpipolarBaseline;
  const Eigen::Matrix3d FA = fundamentalMatrix(map.camera.K(), TAkLin);
  const Eigen::Matrix3d FB = fundamentalMatrix(map.camera.K(), TBkLin);
  const auto sigmaOf = [&](float contrastK, float contrastRef) {
    return std::sqrt(varianceModel.variance(contrastK) + varianceModel.variance(contrastRef));
  };
  const auto gateEpipolar = [&](const std::vector<WideBaselineMatch>& ms,
                                const std::vector<std::size_t>& measurement,
                                const PreparedReference& ref, const Eigen::Matrix3d& F,
                                bool useEpipolar, const std::vector<char>& distinctive,
                                std::vector<char>& inlier, std::vector<EpipolarMatch>& out,
                                std::vector<int>& outCorner, std::vector<std::size_t>& outMatch) {
    const bool inB = &ref == &refB;
    const double group =
        groupFactor(inB ? MeasurementGroup::EpipolarB : MeasurementGroup::EpipolarA);
    inlier.assign(ms.size(), 0);
    for (std::size_t i = 0; i < ms.size(); ++i) {
      const Eigen::Vector2d& pK = meas.undistorted[measurement[i]];
      const auto rc = static_cast<std::size_t>(ms[i].referenceCorner);
      if (maxEpipolarDistance(F, ref.measured[rc], pK) > gate) continue;
      inlier[i] = 1;
      in.distinctive += distinctive[rc] ? 1 : 0;
      if (!useEpipolar) continue;
      const double reliability =
          cornerReliability.varianceFactor(cornerSource(inB, ms[i].referenceCorner));
      out.push_back({ref.measured[rc], pK,
                     sigmaOf(c.corners[static_cast<std::size_t>(ms[i].frameCorner)].contrast,
                             ref.contrast[rc]) *
                         std::sqrt(reliability * group)});
      outCorner.push_back(ms[i].referenceCorner);
      outMatch.push_back(i);
    }
  };
  gateEpipolar(m.toA, meas.toA, refA, FA, useEpipolarA, distinctiveA, in.inlierA,
               in.measurements.toA, in.epipolarCornerA, in.epipolarMatchA);
  gateEpipolar(m.toB, meas.toB, refB, FB, useEpipolarB, distinctiveB, in.inlierB,
               in.measurements.toB, in.epipolarCornerB, in.epipolarMatchB);
  for (const Pair3D& p : pairs) {
    const Eigen::Vector3d& P = map.matches[static_cast<std::size_t>(p.mapMatch)].pointA;
    const Eigen::Vector2d& pK = meas.undistorted[p.measurement];
    if ((map.camera.project(TAkLin * P) - pK).norm() > gate) continue;
    in.threeViewMeasurement.push_back(p.measurement);
    const double sigma =
        varianceModel.sigma(c.corners[static_cast<std::size_t>(p.frameCorner)].contrast);
    ThreeViewMatch t{P, pK, sigma};
    if (params.pose.mapPointSdScale > 0)
      t.whitening = threeViewWhitening(TAkLin, p.mapMatch, sigma);
    const double factor = pointReliability.varianceFactor(static_cast<std::size_t>(p.mapMatch)) *
                          groupFactor(MeasurementGroup::CornerPoints);
    if (factor != 1.0) t.whitening = t.whiteningOrScalar() / std::sqrt(factor);
    in.threeViewMapMatch.push_back(p.mapMatch);
    in.measurements.threeView.push_back(t);
  }
  r.inliers = static_cast<int>(in.measurements.threeView.size());
  r.distinctiveInliers = in.distinctive;
  if (r.inliers < limits.minInliers) {
    lose(r, "too few inliers (" + std::to_string(r.inliers) + ")");
    return std::nullopt;
  }
  return in;
}

// Stage 7b, keypoint measurements (wide_baseline.keypoint_points): the keypoint layer's points
// aligned in the frame around their projections by the robust linear pose (KeypointMeasurer),
// within the gate under it, join the three-view terms (after the corners' own).
void PoseTracker::Impl::measureKeypoints(const cv::Mat& gray, double gate, Inliers& in,
                                         PoseTrackingResult& r) {
  const int cap = params.wideBaseline.keypointPointsFor(gray.size());
  if (cap <= 0 || !keypointMeasurer) return;
  const RigidPose TAkLin = RigidPose::fromVector6(in.xLin);
  const std::vector<KeypointMeasurement> found = keypointMeasurer->measure(gray, TAkLin, cap);
  // Each aligned point's term (undistorted, gated, whitened) on its own, in two shares at once
  // (OpenCV's threads; the same terms on any number of threads), then appended in order.
  const double floor = params.wideBaseline.keypointSigmaPx;
  std::vector<std::optional<ThreeViewMatch>> terms(found.size());
  cv::parallel_for_(
      cv::Range(0, static_cast<int>(found.size())),
      [&](const cv::Range& range) {
        std::vector<cv::Point2f> pixels;
        for (int i = range.start; i < range.end; ++i)
          pixels.push_back(found[static_cast<std::size_t>(i)].pixel);
        const std::vector<cv::Point2f> undistorted = map.camera.undistortPixels(pixels);
        for (int i = range.start; i < range.end; ++i) {
          const KeypointMeasurement& k = found[static_cast<std::size_t>(i)];
          const auto point = static_cast<std::size_t>(k.point);
          const Eigen::Vector3d& P = keypointMeasurer->points()[point].pointA;
          const Eigen::Vector2d pK =
              toEigen(undistorted[static_cast<std::size_t>(i - range.start)]);
          if ((map.camera.project(TAkLin * P) - pK).norm() > gate) continue;
          ThreeViewMatch t{P, pK, std::max(floor, k.sigmaPx)};
          if (params.pose.mapPointSdScale > 0)
            t.whitening = threeViewWhitening(TAkLin, P, keypointCovariance(P), t.sigma);
          const double factor = pointReliability.varianceFactor(map.matches.size() + point) *
                                groupFactor(MeasurementGroup::KeypointPoints);
          if (factor != 1.0) t.whitening = t.whiteningOrScalar() / std::sqrt(factor);
          terms[static_cast<std::size_t>(i)] = t;
        }
      },
      found.size() >= 64 ? 2 : 1);
  for (std::size_t i = 0; i < found.size(); ++i) {
    if (!terms[i]) continue;
    in.threeViewMapMatch.push_back(static_cast<int>(map.matches.size()) + found[i].point);
    in.measurements.threeView.push_back(*terms[i]);
    ++r.keypointMeasurements;
  }
}

// Stage 9, support: the estimate must be finite with a sane covariance, fit its three-view
// matches, and the matches alone must pin the scene's image position down (PoseSupport: black,
// textureless and heavily blurred frames fail here). Judged on the first `supportTerms` three-view
// terms (the corners'; keypoint terms follow them). The reason it fails (sets r.supportSdPx), or
// nullopt when it holds.
std::optional<std::string> PoseTracker::Impl::supportFailure(const PoseEstimate& est,
                                                             const PoseMeasurements& meas,
                                                             std::size_t supportTerms, double scale,
                                                             PoseTrackingResult& r) const {
  const RigidPose TAk = RigidPose::fromVector6(est.x);
  const std::size_t n = std::min(supportTerms, meas.threeView.size());
  const std::span<const ThreeViewMatch> support(meas.threeView.data(), n);
  double sse = 0.0;
  for (const ThreeViewMatch& t : support)
    sse += (map.camera.project(TAk * t.pointA) - t.pK).squaredNorm();
  const double rms = std::sqrt(sse / static_cast<double>(std::max<std::size_t>(n, 1)));
  const double sigmaT = std::sqrt(est.covariance.topLeftCorner<3, 3>().diagonal().maxCoeff());
  if (!est.covarianceValid || !std::isfinite(sigmaT) || sigmaT > limits.maxSigmaTranslation)
    return est.covarianceValid ? "pose covariance blew up (translation SD " +
                                     std::to_string(sigmaT * 1000.0) + " mm)"
                               : std::string("pose covariance is not positive definite");
  if (rms > limits.maxRmsPx * scale)
    return "reprojection RMS " + std::to_string(rms) + " px at the solution is too large";
  const std::optional<double> supportSd = reprojectionSupportSdPx(map.camera, TAk, support);
  r.supportSdPx = supportSd.value_or(INFINITY);
  if (!supportSd || *supportSd > limits.maxSupportSdPx * scale)
    return "too little support: the matches fix the scene's image position only to " +
           std::to_string(r.supportSdPx) + " px (SD)";
  return std::nullopt;
}

// Stage 9b, verification: the pose's own projections of the distinctive map points must be
// confirmed by the frame (PoseVerifier); the matches that produced it are not consulted. False
// (with the reason in r) otherwise.
bool PoseTracker::Impl::verifyPose(const cv::Mat& frame, const cv::Mat& gray, const RigidPose& TAk,
                                   bool trackedOn, PoseTrackingResult& r) {
  if (params.pose.verifyMinPoints <= 0) return true;
  Clock::time_point t = Clock::now();
  const PoseCheck check = verifier->check(gray, TAk);
  r.verifyCheckable = check.checkable;
  r.verifyConfirmed = check.confirmed;
  r.timings.push_back({"verify", msSince(t)});
  if (check.passed()) return true;
  std::string why = check.reason;
  if (confirmation) {
    const bool unsure = check.verdict == PoseCheck::Verdict::Unsure;
    // An unbroken track whose last unsure pose the second opinion kept: that opinion stands for
    // the next pose.verify_unsure_every_frames - 1 frames (no relocaliser run, no "confirm").
    if (unsure && trackedOn && framesSinceOpinion >= 0 &&
        framesSinceOpinion < params.pose.verifyUnsureEveryFrames) {
      r.confirmedBySecondOpinion = true;
      return true;
    }
    t = Clock::now();
    const std::optional<std::string> refused =
        confirmation(frame, {TAk * map.T_A, unsure, trackedOn});
    r.timings.push_back({"confirm", msSince(t)});
    if (!refused) {
      r.confirmedBySecondOpinion = true;
      if (unsure && trackedOn) framesSinceOpinion = 0;
      return true;
    }
    why += "; " + *refused;
  }
  lose(r, why);
  r.verificationFailed = true;
  return false;
}

// Stage 10, seeds for the next frame: the inlier matches (and the debug primitives).
void PoseTracker::Impl::keepInliers(const FrameCorners& c, const FrameMatches& m, const Inliers& in,
                                    PoseTrackingResult& r) {
  prevA.clear();
  prevB.clear();
  const auto keep = [&](const std::vector<WideBaselineMatch>& ms, const std::vector<char>& inlier,
                        const PreparedReference& ref, std::vector<PreviousMatch>& previous,
                        std::vector<std::pair<cv::Point2f, cv::Point2f>>& debug) {
    for (std::size_t i = 0; i < ms.size(); ++i) {
      if (!inlier[i]) continue;
      const cv::Point2f p = c.pixels[static_cast<std::size_t>(ms[i].frameCorner)];
      previous.push_back({p, ms[i].referenceCorner});
      debug.emplace_back(p, ref.matchable.corners[static_cast<std::size_t>(ms[i].referenceCorner)]);
    }
  };
  keep(m.toA, in.inlierA, refA, prevA, r.inliersA);
  keep(m.toB, in.inlierB, refB, prevB, r.inliersB);
}

// Stage 10b, learned reliability: each term's residual at the accepted pose, whitened by its
// modelled variance (the reliability factor it was weighted with taken out), held until the next
// frame goes on from this one (process() commits or drops them).
void PoseTracker::Impl::recordResiduals(const RigidPose& TAk, const Inliers& in) {
  pendingReliability.clear();
  const PoseMeasurements& pm = in.measurements;
  const TermResiduals w = whitenedResiduals(TAk, pm);
  MeasurementGroupNoise::FrameResiduals groups;
  const double cornerGroup = groupFactor(MeasurementGroup::CornerPoints);
  const double keypointGroup = groupFactor(MeasurementGroup::KeypointPoints);
  for (std::size_t i = 0; i < pm.threeView.size(); ++i) {
    const auto source = static_cast<std::size_t>(in.threeViewMapMatch[i]);
    const bool corner = i < in.threeViewMeasurement.size();
    const double group = corner ? cornerGroup : keypointGroup;
    // Per image axis, without this source's factor (MeasurementReliability::observe) ...
    pendingReliability.push_back(
        {true, source, 0.5 * w.threeView[i] * group * pointReliability.varianceFactor(source)});
    // ... and without its kind's (MeasurementGroupNoise::observe).
    groups
        .whitenedSquared[static_cast<std::size_t>(corner ? MeasurementGroup::CornerPoints
                                                         : MeasurementGroup::KeypointPoints)]
        .push_back(w.threeView[i] * group);
  }
  const auto epipolar = [&](const std::vector<double>& squared, const std::vector<int>& corners,
                            bool inB) {
    const MeasurementGroup kind = inB ? MeasurementGroup::EpipolarB : MeasurementGroup::EpipolarA;
    const double group = groupFactor(kind);
    for (std::size_t i = 0; i < squared.size(); ++i) {
      const std::size_t source = cornerSource(inB, corners[i]);
      pendingReliability.push_back(
          {false, source, squared[i] * group * cornerReliability.varianceFactor(source)});
      groups.whitenedSquared[static_cast<std::size_t>(kind)].push_back(squared[i] * group);
    }
  };
  epipolar(w.toA, in.epipolarCornerA, false);
  epipolar(w.toB, in.epipolarCornerB, true);
  pendingGroupResiduals = std::move(groups);
}

PoseTracker::Impl::TermResiduals PoseTracker::Impl::whitenedResiduals(
    const RigidPose& TAk, const PoseMeasurements& pm) const {
  TermResiduals out;
  for (const ThreeViewMatch& t : pm.threeView)
    out.threeView.push_back(
        (t.whiteningOrScalar() * (map.camera.project(TAk * t.pointA) - t.pK)).squaredNorm());
  const auto epipolar = [&](const std::vector<EpipolarMatch>& terms, const RigidPose& refToK,
                            std::vector<double>& squared) {
    const Eigen::Matrix3d F = fundamentalMatrix(map.camera.K(), refToK);
    for (const EpipolarMatch& e : terms) {
      const Eigen::Vector3d line = F * Eigen::Vector3d(e.pRef.x(), e.pRef.y(), 1.0);
      const double distance =
          Eigen::Vector3d(e.pK.x(), e.pK.y(), 1.0).dot(line) / std::hypot(line.x(), line.y());
      squared.push_back(distance * distance / (e.sigma * e.sigma));
    }
  };
  epipolar(pm.toA, TAk, out.toA);
  epipolar(pm.toB, TAk * map.T_AB().inverse(), out.toB);
  return out;
}

// Stage 8b, outlier terms: at the estimate, each kind of term (corner points, keypoint points,
// epipolar to A, to B) has its robust scale (median); a term beyond pose.reject_sigmas times it
// (and at least that many modelled SDs) is dropped, unless too few corner points would remain.
// The count dropped; the caller estimates the pose again.
int PoseTracker::Impl::dropOutlierTerms(const RigidPose& TAk, Inliers& in) const {
  const double k = params.pose.rejectSigmas;
  if (!(k > 0)) return 0;
  PoseMeasurements& pm = in.measurements;
  const TermResiduals w = whitenedResiduals(TAk, pm);
  const auto boundOf = [&](const std::vector<double>& squared, std::size_t from, std::size_t to,
                           ResidualDimension dimension) {
    std::vector<double> norms;
    for (std::size_t i = from; i < to; ++i) norms.push_back(std::sqrt(squared[i]));
    if (static_cast<int>(norms.size()) < MeasurementGroupNoise::kMinTerms)
      return std::numeric_limits<double>::infinity();
    const double bound = k * std::max(1.0, robustSd(norms, dimension));
    return bound * bound;
  };
  const std::size_t corners = in.threeViewMeasurement.size();
  const double cornerBound = boundOf(w.threeView, 0, corners, ResidualDimension::Two);
  const double keypointBound =
      boundOf(w.threeView, corners, w.threeView.size(), ResidualDimension::Two);
  int keptCorners = 0;
  for (std::size_t i = 0; i < corners; ++i) keptCorners += w.threeView[i] <= cornerBound ? 1 : 0;
  if (keptCorners < limits.minInliers) return 0;
  int dropped = 0;
  {
    PoseMeasurements kept;
    std::vector<std::size_t> measurement;
    std::vector<int> mapMatch;
    for (std::size_t i = 0; i < pm.threeView.size(); ++i) {
      const bool corner = i < corners;
      if (w.threeView[i] > (corner ? cornerBound : keypointBound)) {
        ++dropped;
        continue;
      }
      kept.threeView.push_back(pm.threeView[i]);
      if (corner) measurement.push_back(in.threeViewMeasurement[i]);
      mapMatch.push_back(in.threeViewMapMatch[i]);
    }
    pm.threeView = std::move(kept.threeView);
    in.threeViewMeasurement = std::move(measurement);
    in.threeViewMapMatch = std::move(mapMatch);
  }
  const auto epipolar = [&](const std::vector<double>& squared, std::vector<EpipolarMatch>& terms,
                            std::vector<int>& corner, std::vector<std::size_t>& match,
                            std::vector<char>& inlier) {
    const double bound = boundOf(squared, 0, squared.size(), ResidualDimension::One);
    std::vector<EpipolarMatch> keptTerms;
    std::vector<int> keptCorner;
    std::vector<std::size_t> keptMatch;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      if (squared[i] > bound) {
        ++dropped;
        inlier[match[i]] = 0;  // no seed for the next frame either
        continue;
      }
      keptTerms.push_back(terms[i]);
      keptCorner.push_back(corner[i]);
      keptMatch.push_back(match[i]);
    }
    terms = std::move(keptTerms);
    corner = std::move(keptCorner);
    match = std::move(keptMatch);
  };
  epipolar(w.toA, pm.toA, in.epipolarCornerA, in.epipolarMatchA, in.inlierA);
  epipolar(w.toB, pm.toB, in.epipolarCornerB, in.epipolarMatchB, in.inlierB);
  return dropped;
}

PoseTrackingResult PoseTracker::Impl::process(const cv::Mat& frame) {
  const Clock::time_point start = Clock::now();
  PoseTrackingResult r;
  r.state = state;
  if (frame.empty()) throw Error("PoseTracker: empty frame");
  if (frame.size() != map.camera.imageSize())
    throw Error("PoseTracker: frame size " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + " differs from the map's camera " +
                std::to_string(map.camera.imageSize().width) + "x" +
                std::to_string(map.camera.imageSize().height));
  const cv::Mat gray = toGray8(frame);
  const double scale = resolutionScale(gray.size());
  const double gate = limits.gatePx * scale;
  if (!seedPose && state == TrackingState::Tracking) {
    for (const PendingObservation& o : pendingReliability)
      (o.point ? pointReliability : cornerReliability).observe(o.source, o.whitenedSquared);
    if (pendingGroupResiduals) groupNoise.observe(std::move(*pendingGroupResiduals));
  }
  pendingReliability.clear();
  pendingGroupResiduals.reset();

  // 1. Corners.
  Clock::time_point t = Clock::now();
  FrameCorners corners = detectCorners(gray);
  r.corners = static_cast<int>(corners.corners.size());
  r.frameCorners = corners.pixels;
  r.timings.push_back({"corners", msSince(t)});
  // A seeded frame is matched like a tracked one, from the seed's projections (seedsFromPose).
  const std::optional<RigidPose> seeded = std::exchange(seedPose, std::nullopt);
  const bool wideSeed = seeded && !std::exchange(tightSeed, false);
  const bool wasTracking = seeded || (state == TrackingState::Tracking && !prevA.empty());
  auto finish = [&](PoseTrackingResult& res) {
    res.totalMs = msSince(start);
    prevF2F = std::move(corners.f2fPoints);
    prevF2FWindows = std::move(corners.f2fWindows);
    return res;
  };
  if (r.corners < limits.minCorners) {
    lose(r, "too few corners (" + std::to_string(r.corners) +
                "): textureless, black or blurred frame");
    return finish(r);
  }

  // 2-4. Matches to V_A and V_B: frame to frame and wide baseline while tracking (or from a
  // seed), else the paper's initialisation; then completed through the map's A<->B matches.
  FrameMatches matches;
  if (wasTracking) {
    // The prediction (stage 2, or the seed's) and the frame's correlation windows for stage 3a
    // at once, one task each on OpenCV's threads (one thread: in turn); frame to frame, also the
    // local affine maps to the previous frame at each reference's corners (the part of 3a that
    // does not depend on H; a seed sets the previous matches, so after one they come in 3a).
    // No task reads what another writes.
    std::optional<MatchableFrame> matchable;
    MapsToPrevious mapsA, mapsB;
    const WideBaselineMatcher wide(params.wideBaseline);
    // The cap counts the corners predicted inside the frame, so the maps cover a quarter more
    // places of the order than the cap; any further ones come in 3a.
    const int cap = params.wideBaseline.referenceCornersFor(gray.size());
    const auto mapsCount = [&](const MatchableReference& ref) {
      return cap > 0 ? static_cast<std::size_t>(cap + cap / 4) : ref.order.size();
    };
    double msPrediction = 0.0, msWindows = 0.0;
    cv::parallel_for_(cv::Range(0, seeded ? 2 : 4), [&](const cv::Range& range) {
      for (int task = range.start; task < range.end; ++task) {
        const Clock::time_point began = Clock::now();
        if (task == 0) {
          if (seeded)
            seedsFromPose(*seeded, gray.size());
          else
            matchFrameToFrame(corners, scale, matches);
          msPrediction = msSince(began);
        } else if (task == 1) {
          matchable = MatchableFrame::build(gray, corners.pixels, params.wideBaseline.halfWindow);
          msWindows = msSince(began);
        } else if (task == 2) {
          mapsA = wide.mapsToPrevious(prevA, refA.matchable, mapsCount(refA.matchable));
        } else {
          mapsB = wide.mapsToPrevious(prevB, refB.matchable, mapsCount(refB.matchable));
        }
      }
    });
    r.timings.push_back({seeded ? "seed" : "frame-to-frame", msPrediction});
    r.timings.push_back({"frame windows", msWindows});
    matchWideBaseline(*matchable, wideSeed, matches, r, seeded ? nullptr : &mapsA,
                      seeded ? nullptr : &mapsB);
  } else {
    t = Clock::now();
    matchInitial(gray, corners, matches);
    r.timings.push_back({"initialise", msSince(t)});
  }
  completeThroughMap(corners.pixels.size(), matches);
  r.matchesA = static_cast<int>(matches.toA.size());
  r.matchesB = static_cast<int>(matches.toB.size());

  // 5. Measurements (frame-side alignment, rolling shutter, lens).
  t = Clock::now();
  const Measurements meas = measure(gray, corners, matches);
  r.rollingShutterReadout = meas.readout;
  r.timings.push_back({"measure", msSince(t)});

  // 6-7. Three-view pairs, outlier rejection.
  t = Clock::now();
  const std::vector<Pair3D> pairs = threeViewPairs(matches, meas);
  r.threeView = static_cast<int>(pairs.size());
  std::optional<Inliers> inliers = rejectOutliers(corners, matches, meas, pairs, gate, r);
  r.timings.push_back({"outliers", msSince(t)});
  if (!inliers) return finish(r);
  // 7b. The keypoint layer's terms; the frame's corner terms are kept aside (8c).
  std::optional<Inliers> cornerTerms;
  if (params.wideBaseline.keypointPointsAt320x240 > 0) {
    t = Clock::now();
    cornerTerms = *inliers;
    measureKeypoints(gray, gate, *inliers, r);
    if (r.keypointMeasurements == 0) cornerTerms.reset();
    r.timings.push_back({"keypoints", msSince(t)});
  }

  // 8. Pose: standard least squares or the temporal regulariser (Eq. 12 / Eq. 13).
  t = Clock::now();
  std::optional<PoseEstimate> est =
      regularizer->step(*estimator, inliers->measurements, inliers->xLin);
  // 8b. Terms far off their kind's scale at the estimate dropped, and the frame estimated again.
  const auto dropAndRedo = [&] {
    if (est && est->x.allFinite() &&
        dropOutlierTerms(RigidPose::fromVector6(est->x), *inliers) > 0) {
      est = regularizer->redoLastStep(*estimator, inliers->measurements, inliers->xLin);
      r.inliers = static_cast<int>(inliers->threeViewMeasurement.size());
    }
  };
  dropAndRedo();
  // 8c. With keypoint terms the support is the corners' alone: aligned around the linear pose, the
  // keypoints confirm whatever pose they start from and passed the check in frames the corners do
  // not pin down (Kinect poses 2-47 px off), and after a jump onto look-alikes they outweighed the
  // few corners (shuffled ViSP: poses 75-78 px off). A joint pose that fails it, or does not
  // converge, gives way to the corners' own.
  std::optional<std::string> unsupported;  // stage 9's verdict, once it is known
  bool supportKnown = false;
  if (cornerTerms) {
    if (est && est->x.allFinite()) {
      unsupported = supportFailure(*est, inliers->measurements,
                                   inliers->threeViewMeasurement.size(), scale, r);
      supportKnown = !unsupported;
    }
    if (!supportKnown) {
      *inliers = std::move(*cornerTerms);
      r.keypointMeasurements = 0;
      r.inliers = static_cast<int>(inliers->threeViewMeasurement.size());
      est = regularizer->redoLastStep(*estimator, inliers->measurements, inliers->xLin);
      dropAndRedo();
    }
  }
  r.timings.push_back({"pose", msSince(t)});
  if (!est || !est->x.allFinite()) {
    lose(r, "the pose estimator did not converge");
    return finish(r);
  }

  // 9. Support (already judged in 8c when the joint pose held).
  if (!supportKnown)
    unsupported =
        supportFailure(*est, inliers->measurements, inliers->threeViewMeasurement.size(), scale, r);
  if (unsupported) {
    lose(r, *unsupported);
    return finish(r);
  }
  const RigidPose TAk = RigidPose::fromVector6(est->x);
  // 9a. A jump: the pose moved the scene farther since the last frame than the wide-baseline
  // search reaches (a cut, dropped frames, a covered lens). Its matches were sought around
  // predictions from before the jump, so on repeated texture part of them are look-alikes and the
  // pose, though close, is a few pixels off (on the shuffled desk clip 3-9 px at the cube after
  // jumps of 57-97 px; in order the points move at most 17 px between frames, 31 px at every 4th
  // frame). The same frame is matched again around this pose, as a seed, and that pass decides.
  if (!seeded && lastTAk) {
    const double moved = medianImageMotion(map.camera, *lastTAk, TAk, inliers->measurements);
    const double reach = std::max(params.wideBaseline.dx, params.wideBaseline.dy) * scale;
    if (moved > reach) {
      PoseTrackingResult again = matchAgainAround(frame, TAk, "jump", start);
      if (again.state == TrackingState::Tracking) {
        char text[120];
        std::snprintf(text, sizeof text,
                      "tracking, matched again around its own pose after a jump of %.0f px", moved);
        again.message = text;
      }
      return again;
    }
  }

  // 9b. The pose itself checked against the references (PoseVerifier), whatever produced it.
  if (!verifyPose(frame, gray, TAk, !seeded, r)) return finish(r);
  // 9c. A pose from a seed's wide search (a relocalisation candidate, a re-seed from the last pose,
  // a hand-over, a start's confirmation) is matched once more around itself within the tracking
  // window: the wide search also reaches look-alikes on repeated texture, and on the shuffled
  // desk clip a re-seed from a far last pose kept 23-26 such matches and a pose 3-4 px off.
  if (wideSeed) return matchAgainAround(frame, TAk, "wide seed", start);
  r.message = seeded        ? "tracking from a seeded pose"
              : wasTracking ? "tracking"
                            : "initialised from the reference images";
  r.state = TrackingState::Tracking;
  state = TrackingState::Tracking;
  r.T_Ak = TAk;
  lastTAk = TAk;
  if (framesSinceOpinion >= 0) ++framesSinceOpinion;
  r.worldToCamera = TAk * map.T_A;
  r.covariance = est->covariance;
  for (const ThreeViewMatch& m : inliers->measurements.threeView)
    r.supportPointsA.push_back(m.pointA);
  if (!meas.shiftPerReadout.empty()) {
    // The tracked frame's residuals inform the readout's estimate (used from a later frame on).
    std::vector<RollingShutterObservation> observations;
    const PoseMeasurements& pm = inliers->measurements;
    observations.reserve(inliers->threeViewMeasurement.size());
    // The corners' terms (the keypoint terms after them have no frame-to-frame shift).
    for (std::size_t i = 0; i < inliers->threeViewMeasurement.size(); ++i) {
      const ThreeViewMatch& x = pm.threeView[i];
      const Eigen::Vector3d X = TAk * x.pointA;
      observations.push_back({X, map.camera.project(X) - x.pK,
                              meas.shiftPerReadout[inliers->threeViewMeasurement[i]], x.sigma});
    }
    shutter->addFrame(map.camera.K()(0, 0), map.camera.K()(1, 1), observations);
  }

  // 10. Seeds for the next frame, and the residuals that teach the learned reliability.
  keepInliers(corners, matches, *inliers, r);
  recordResiduals(TAk, *inliers);
  return finish(r);
}

PoseTracker::PoseTracker(ReferenceMap map, const TrackerParams& params, PoseTrackerLimits limits)
    : impl_(std::make_unique<Impl>(std::move(map), params, limits)) {}
PoseTracker::~PoseTracker() = default;
PoseTrackingResult PoseTracker::process(const cv::Mat& frame) { return impl_->process(frame); }
void PoseTracker::setParams(const TrackerParams& params) {
  params.check();
  if (params.pose.rollingShutterReadout != impl_->params.pose.rollingShutterReadout ||
      params.pose.estimateRollingShutter != impl_->params.pose.estimateRollingShutter)
    impl_->shutter->reset(params.pose.rollingShutterReadout);
  impl_->params = params;
  impl_->applyCornerParams();
  impl_->applyPoseParams();
  impl_->computeDistinctiveCorners();  // and the verifier with its parameters
  impl_->computePointCovariances();
  impl_->pointReliability.setPriorObservations(params.pose.reliabilityPriorObservations);
  impl_->cornerReliability.setPriorObservations(params.pose.reliabilityPriorObservations);
}
void PoseTracker::setMotionModel(const ArMotionModel& model) {
  model.check();
  impl_->motionModel = model;
  impl_->regularizer->setModel(model);
}
void PoseTracker::setCornerVarianceModel(const CornerVarianceModel& model) {
  model.check();
  impl_->varianceModel = model;
  impl_->computePointCovariances();
}
void PoseTracker::seed(const RigidPose& worldToCamera) {
  if (!worldToCamera.allFinite()) throw Error("PoseTracker::seed: non-finite pose");
  impl_->seedWith(worldToCamera, false);
}
void PoseTracker::forgetLearnedReliability() {
  impl_->pointReliability.clear();
  impl_->cornerReliability.clear();
  impl_->pendingReliability.clear();
  impl_->groupNoise.clear();
  impl_->pendingGroupResiduals.reset();
}
void PoseTracker::reset() {
  impl_->seedPose.reset();
  impl_->framesSinceOpinion = -1;
  impl_->tightSeed = false;
  impl_->lastTAk.reset();
  impl_->state = TrackingState::Initialising;
  impl_->regularizer->reset();
  impl_->prevA.clear();
  impl_->prevB.clear();
  impl_->pendingReliability.clear();
  impl_->pendingGroupResiduals.reset();
}
void PoseTracker::setVerificationKeypoints(std::vector<VerificationKeypoint> inA,
                                           std::vector<VerificationKeypoint> inB) {
  impl_->verificationKeypoints[0] = std::move(inA);
  impl_->verificationKeypoints[1] = std::move(inB);
  impl_->buildVerifier();  // the reference corners' distinctiveness is unchanged
}
void PoseTracker::setPoseConfirmation(PoseConfirmation confirmation) {
  impl_->confirmation = std::move(confirmation);
}
void PoseTracker::shareRollingShutterEstimator(std::shared_ptr<RollingShutterEstimator> shared) {
  if (!shared) throw Error("PoseTracker::shareRollingShutterEstimator: null estimator");
  impl_->shutter = std::move(shared);
}
double PoseTracker::rollingShutterReadout() const { return impl_->readout(); }
const ReferenceMap& PoseTracker::map() const { return impl_->map; }
TrackingState PoseTracker::state() const { return impl_->state; }

}  // namespace reftrack
