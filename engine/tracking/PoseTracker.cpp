#include "engine/tracking/PoseTracker.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/estimation/MotionModelFile.hpp"
#include "engine/estimation/RegularizedPoseEstimator.hpp"
#include "engine/estimation/RollingShutterEstimator.hpp"
#include "engine/estimation/TemporalRegularizer.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/geometry/FundamentalMatrix.hpp"
#include "engine/matching/NarrowBaselineMatcher.hpp"
#include "engine/tracking/PoseSupport.hpp"
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
  for (std::size_t i = 0; i < peakCorners.size(); ++i)
    r.measured[peakCorners[i]] = toEigen(undistortedPeaks[i]);
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

  Impl(ReferenceMap m, const TrackerParams& p, PoseTrackerLimits l)
      : map(std::move(m)), params(p), limits(l) {
    map.check();
    params.check();
    limits.check();
    refA = prepare(map.imageA, map.cornersA, map.camera, map.matches, true);
    refB = prepare(map.imageB, map.cornersB, map.camera, map.matches, false);
    estimator = std::make_unique<RegularizedPoseEstimator>(map.camera.K(), map.T_AB());
    applyCornerParams();
    applyPoseParams();
    shutter = std::make_shared<RollingShutterEstimator>(params.pose.rollingShutterReadout);
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
    detector = std::make_unique<CornerDetector>(cornerParams);
  }

  void applyPoseParams() {
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
    regularizer->reset();
    prevA.clear();
    prevB.clear();
    prevFrameToFrame.reset();
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

  PoseTrackingResult process(const cv::Mat& frame);
};

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

  Clock::time_point t = Clock::now();
  const std::vector<Corner> corners = detector->detect(gray);
  const std::vector<cv::Point2f> pixels = positionsOf(corners);
  r.corners = static_cast<int>(corners.size());
  r.frameCorners = pixels;
  r.timings.push_back({"corners", msSince(t)});
  // A seeded frame is matched like a tracked one, from the seed's projections (seedsFromPose).
  const std::optional<RigidPose> seeded = std::exchange(seedPose, std::nullopt);
  const bool wasTracking = seeded || (state == TrackingState::Tracking && !prevA.empty());
  // Frame-to-frame matching only predicts W = L H (Eq. 18): the strongest corners suffice, and
  // their windows are kept for the next frame.
  const std::size_t f2fCount = std::min<std::size_t>(
      pixels.size(),
      static_cast<std::size_t>(params.wideBaseline.frameToFrameCornersFor(gray.size())));
  std::vector<cv::Point2f> f2fPoints(pixels.begin(), pixels.begin() + static_cast<long>(f2fCount));
  NccPatches f2fWindows = NccPatches::square(gray, f2fPoints, params.correlation.halfWindow);
  auto finish = [&](PoseTrackingResult& res) {
    res.totalMs = msSince(start);
    prevF2F = std::move(f2fPoints);
    prevF2FWindows = std::move(f2fWindows);
    return res;
  };
  if (r.corners < limits.minCorners) {
    lose(r, "too few corners (" + std::to_string(r.corners) +
                "): textureless, black or blurred frame");
    return finish(r);
  }
  std::vector<Eigen::Vector2d> undist;
  // The frame-to-frame homography V_k -> V_{k-1} of a tracked frame (identity otherwise).
  cv::Matx33d H = cv::Matx33d::eye();
  bool haveFrameToFrame = false;

  // ---- Matches to V_A and V_B (frame corner index -> reference corner index).
  std::vector<WideBaselineMatch> mA, mB;
  const NarrowBaselineMatcher narrow(params.correlation);
  if (wasTracking) {
    t = Clock::now();
    // Frame-to-frame homography V_k -> V_{k-1}: only a prediction for W = L H (Eq. 18), so
    // OpenCV's RANSAC homography suffices here; a failure falls back to the identity. A seeded
    // frame's "previous frame" is the seed's projection of the map: H is the identity.
    WideBaselineParams wideParams = params.wideBaseline;
    if (seeded) {
      seedsFromPose(*seeded, gray.size());
      wideParams.dx = wideParams.dy = wideParams.seedSearchAt320x240;
    }
    const std::vector<CornerMatch> f2f =
        seeded ? std::vector<CornerMatch>{}
               : narrow.match(f2fPoints, f2fWindows, prevF2F, prevF2FWindows,
                              params.correlation.searchHalfWidthPx * scale,
                              params.correlation.searchHalfHeightPx * scale);
    if (f2f.size() >= 8) {
      std::vector<cv::Point2f> a, b;
      for (const CornerMatch& m : f2f) {
        a.push_back(f2fPoints[static_cast<std::size_t>(m.first)]);
        b.push_back(prevF2F[static_cast<std::size_t>(m.second)]);
      }
      const cv::Mat Hm = cv::findHomography(a, b, cv::RANSAC, 3.0 * scale);
      if (!Hm.empty()) {
        H = cv::Matx33d(Hm);
        haveFrameToFrame = true;
      }
    }
    r.timings.push_back({seeded ? "seed" : "frame-to-frame", msSince(t)});
    t = Clock::now();
    // The frame's correlation windows, sampled once for both references.
    const MatchableFrame matchable =
        MatchableFrame::build(gray, pixels, params.wideBaseline.halfWindow);
    r.timings.push_back({"frame windows", msSince(t)});
    const WideBaselineMatcher wide(wideParams);
    t = Clock::now();
    mA = wide.match(matchable, H, prevA, refA.matchable);
    r.timings.push_back({"match A", msSince(t)});
    t = Clock::now();
    mB = wide.match(matchable, H, prevB, refB.matchable);
    r.timings.push_back({"match B", msSince(t)});
  } else {
    // Initialisation (paper Sec. 6.2): narrow-baseline matching to V_A; V_B follows through the
    // stored A<->B matches. A frame near V_B initialises symmetrically.
    t = Clock::now();
    std::vector<CornerMatch> nA = narrow.match(gray, corners, refA.gray, refA.asCorners);
    std::vector<CornerMatch> nB = narrow.match(gray, corners, refB.gray, refB.asCorners);
    if (nA.size() + nB.size() < static_cast<std::size_t>(4 * limits.minInliers)) {
      // Paper Sec. 6.2 starts only from a frame near V_A; a frame along the same line of sight
      // but at another distance starts too once its windows are resampled to the right scale.
      const double s = kInitScales[nextInitScale++ % std::size(kInitScales)];
      std::vector<CornerMatch> sA = matchAtScale(narrow, gray, pixels, refA, s);
      std::vector<CornerMatch> sB = matchAtScale(narrow, gray, pixels, refB, s);
      if (sA.size() + sB.size() > nA.size() + nB.size()) {
        nA = std::move(sA);
        nB = std::move(sB);
      }
    }
    for (const CornerMatch& m : nA) mA.push_back({m.first, m.second, m.score, {}});
    for (const CornerMatch& m : nB) mB.push_back({m.first, m.second, m.score, {}});
    r.timings.push_back({"initialise", msSince(t)});
  }
  // Matches implied through the map's A<->B matches complete the other side.
  {
    std::vector<int> frameToB(pixels.size(), -1), frameToA(pixels.size(), -1);
    for (const WideBaselineMatch& m : mB)
      frameToB[static_cast<std::size_t>(m.frameCorner)] = m.referenceCorner;
    for (const WideBaselineMatch& m : mA)
      frameToA[static_cast<std::size_t>(m.frameCorner)] = m.referenceCorner;
    std::vector<char> usedB(refB.undistorted.size(), 0), usedA(refA.undistorted.size(), 0);
    for (const WideBaselineMatch& m : mB) usedB[static_cast<std::size_t>(m.referenceCorner)] = 1;
    for (const WideBaselineMatch& m : mA) usedA[static_cast<std::size_t>(m.referenceCorner)] = 1;
    const std::size_t nA0 = mA.size(), nB0 = mB.size();
    for (std::size_t i = 0; i < nA0; ++i) {
      const int mm = refA.mapMatch[static_cast<std::size_t>(mA[i].referenceCorner)];
      if (mm < 0) continue;
      const int b = map.matches[static_cast<std::size_t>(mm)].cornerB;
      if (frameToB[static_cast<std::size_t>(mA[i].frameCorner)] < 0 &&
          !usedB[static_cast<std::size_t>(b)]) {
        mB.push_back({mA[i].frameCorner, b, mA[i].score, {}});
        usedB[static_cast<std::size_t>(b)] = 1;
      }
    }
    for (std::size_t i = 0; i < nB0; ++i) {
      const int mm = refB.mapMatch[static_cast<std::size_t>(mB[i].referenceCorner)];
      if (mm < 0) continue;
      const int a = map.matches[static_cast<std::size_t>(mm)].cornerA;
      if (frameToA[static_cast<std::size_t>(mB[i].frameCorner)] < 0 &&
          !usedA[static_cast<std::size_t>(a)]) {
        mA.push_back({mB[i].frameCorner, a, mB[i].score, {}});
        usedA[static_cast<std::size_t>(a)] = 1;
      }
    }
  }
  r.matchesA = static_cast<int>(mA.size());
  r.matchesB = static_cast<int>(mB.size());
  // Per frame corner, how far its undistorted measurement moves per unit of readout (for the
  // readout's online estimate; empty when it is off or the frame has no frame-to-frame motion).
  std::vector<Eigen::Vector2d> shiftPerReadout;
  const double readoutUsed = readout();
  r.rollingShutterReadout = readoutUsed;
  {
    // Rolling shutter (pose.rolling_shutter_readout): row y was exposed (y - c) / (rows - 1)
    // readouts after the middle row c; the corner moves back along its image velocity (pixels
    // per frame interval) by that fraction of it. Matching keeps the observed pixels.
    const bool estimating = params.pose.estimateRollingShutter && haveFrameToFrame;
    std::vector<cv::Point2f> measured = pixels, unitShifted;
    if ((readoutUsed > 0 || estimating) && haveFrameToFrame) {
      const double middle = 0.5 * (gray.rows - 1);
      if (estimating) unitShifted = pixels;
      for (std::size_t i = 0; i < measured.size(); ++i) {
        cv::Point2f& p = measured[i];
        const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1.0);
        if (!(std::abs(q[2]) > 1e-12)) continue;
        const double f = (p.y - middle) / (gray.rows - 1);
        // The image velocity at the middle row's instant: H gives it half a frame earlier, and
        // the previous frame's homography one and a half; extrapolated linearly (hand-held motion
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
        if (estimating)
          unitShifted[i] -= cv::Point2f(static_cast<float>(dx), static_cast<float>(dy));
        p.x -= static_cast<float>(readoutUsed * dx);
        p.y -= static_cast<float>(readoutUsed * dy);
      }
    }
    for (const cv::Point2f& p : map.camera.undistortPixels(measured)) undist.push_back(toEigen(p));
    prevFrameToFrame = haveFrameToFrame ? std::optional<cv::Matx33d>(H) : std::nullopt;
    if (estimating) {
      const std::vector<cv::Point2f> raw = map.camera.undistortPixels(pixels);
      const std::vector<cv::Point2f> moved = map.camera.undistortPixels(unitShifted);
      for (std::size_t i = 0; i < raw.size(); ++i)
        shiftPerReadout.push_back(toEigen(raw[i]) - toEigen(moved[i]));
    }
  }

  // ---- 3D-2D pairs (map points seen through A or B), PnP-RANSAC, gate.
  t = Clock::now();
  struct Pair3D {
    int frameCorner, mapMatch;
  };
  std::vector<Pair3D> pairs;
  {
    std::vector<char> usedMap(map.matches.size(), 0);
    auto add = [&](const std::vector<WideBaselineMatch>& ms, const PreparedReference& ref) {
      for (const WideBaselineMatch& m : ms) {
        const int mm = ref.mapMatch[static_cast<std::size_t>(m.referenceCorner)];
        if (mm < 0 || usedMap[static_cast<std::size_t>(mm)]) continue;
        usedMap[static_cast<std::size_t>(mm)] = 1;
        pairs.push_back({m.frameCorner, mm});
      }
    };
    add(mA, refA);
    add(mB, refB);
  }
  r.threeView = static_cast<int>(pairs.size());
  if (static_cast<int>(pairs.size()) < limits.minInliers) {
    lose(r, "too few 3D-2D matches (" + std::to_string(pairs.size()) + ")");
    r.timings.push_back({"pose", msSince(t)});
    return finish(r);
  }
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const Pair3D& p : pairs) {
    const Eigen::Vector3d& P = map.matches[static_cast<std::size_t>(p.mapMatch)].pointA;
    object.emplace_back(P.x(), P.y(), P.z());
    const Eigen::Vector2d& q = undist[static_cast<std::size_t>(p.frameCorner)];
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
    r.timings.push_back({"pose", msSince(t)});
    return finish(r);
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
    cv::solvePnPRefineLM(o, im, Kcv, cv::noArray(), rvec, tvec);
  }
  Vector6d xLin;
  xLin << tvec[0], tvec[1], tvec[2], rvec[0], rvec[1], rvec[2];
  const RigidPose TAkLin = RigidPose::fromVector6(xLin);
  const RigidPose TABinv = map.T_AB().inverse();

  // Measurements: residuals under the robust pose decide which matches enter the estimator.
  PoseMeasurements meas;
  std::vector<char> inlierA(mA.size(), 0), inlierB(mB.size(), 0);
  // Near a reference camera the epipolar geometry degenerates (F -> 0 as the baseline vanishes,
  // and the distance's derivatives blow up): below minEpipolarBaseline its terms are left out and
  // the three-view terms carry the pose. The gate above still uses them to reject outliers.
  const RigidPose TBkLin = TAkLin * TABinv;
  const bool useEpipolarA = TAkLin.translation().norm() >= limits.minEpipolarBaseline;
  const bool useEpipolarB = TBkLin.translation().norm() >= limits.minEpipolarBaseline;
  const Eigen::Matrix3d FA = fundamentalMatrix(map.camera.K(), TAkLin);
  const Eigen::Matrix3d FB = fundamentalMatrix(map.camera.K(), TBkLin);
  auto sigmaOf = [&](float contrastK, float contrastRef) {
    return std::sqrt(varianceModel.variance(contrastK) + varianceModel.variance(contrastRef));
  };
  for (std::size_t i = 0; i < mA.size(); ++i) {
    const Eigen::Vector2d& pK = undist[static_cast<std::size_t>(mA[i].frameCorner)];
    const Eigen::Vector2d& pRef = refA.measured[static_cast<std::size_t>(mA[i].referenceCorner)];
    if (maxEpipolarDistance(FA, pRef, pK) > gate) continue;
    inlierA[i] = 1;
    if (!useEpipolarA) continue;
    meas.toA.push_back({pRef, pK,
                        sigmaOf(corners[static_cast<std::size_t>(mA[i].frameCorner)].contrast,
                                refA.contrast[static_cast<std::size_t>(mA[i].referenceCorner)])});
  }
  for (std::size_t i = 0; i < mB.size(); ++i) {
    const Eigen::Vector2d& pK = undist[static_cast<std::size_t>(mB[i].frameCorner)];
    const Eigen::Vector2d& pRef = refB.measured[static_cast<std::size_t>(mB[i].referenceCorner)];
    if (maxEpipolarDistance(FB, pRef, pK) > gate) continue;
    inlierB[i] = 1;
    if (!useEpipolarB) continue;
    meas.toB.push_back({pRef, pK,
                        sigmaOf(corners[static_cast<std::size_t>(mB[i].frameCorner)].contrast,
                                refB.contrast[static_cast<std::size_t>(mB[i].referenceCorner)])});
  }
  std::vector<int> threeViewCorner;  // frame corner of each meas.threeView entry
  for (const Pair3D& p : pairs) {
    const Eigen::Vector3d& P = map.matches[static_cast<std::size_t>(p.mapMatch)].pointA;
    const Eigen::Vector2d& pK = undist[static_cast<std::size_t>(p.frameCorner)];
    if ((map.camera.project(TAkLin * P) - pK).norm() > gate) continue;
    threeViewCorner.push_back(p.frameCorner);
    meas.threeView.push_back(
        {P, pK, varianceModel.sigma(corners[static_cast<std::size_t>(p.frameCorner)].contrast)});
  }
  r.inliers = static_cast<int>(meas.threeView.size());
  if (r.inliers < limits.minInliers) {
    lose(r, "too few inliers (" + std::to_string(r.inliers) + ")");
    r.timings.push_back({"pose", msSince(t)});
    return finish(r);
  }

  r.timings.push_back({"outliers", msSince(t)});
  t = Clock::now();
  // Pose: standard least squares or the temporal regulariser (Eq. 12 / Eq. 13).
  const std::optional<PoseEstimate> est = regularizer->step(*estimator, meas, xLin);
  r.timings.push_back({"pose", msSince(t)});
  if (!est || !est->x.allFinite()) {
    lose(r, "the pose estimator did not converge");
    return finish(r);
  }
  const RigidPose TAk = RigidPose::fromVector6(est->x);
  double sse = 0.0;
  for (const ThreeViewMatch& m : meas.threeView)
    sse += (map.camera.project(TAk * m.pointA) - m.pK).squaredNorm();
  const double rms = std::sqrt(sse / static_cast<double>(meas.threeView.size()));
  const double sigmaT = std::sqrt(est->covariance.topLeftCorner<3, 3>().diagonal().maxCoeff());
  if (!est->covarianceValid || !std::isfinite(sigmaT) || sigmaT > limits.maxSigmaTranslation) {
    lose(r, est->covarianceValid ? "pose covariance blew up (translation SD " +
                                       std::to_string(sigmaT * 1000.0) + " mm)"
                                 : "pose covariance is not positive definite");
    return finish(r);
  }
  if (rms > limits.maxRmsPx * scale) {
    lose(r, "reprojection RMS " + std::to_string(rms) + " px at the solution is too large");
    return finish(r);
  }
  // Support: the pose the matches alone determine, with the residuals they actually show, must
  // pin the scene down in the image (blurred frames: few, poorly localised corners).
  const std::optional<double> supportSd = reprojectionSupportSdPx(map.camera, TAk, meas.threeView);
  r.supportSdPx = supportSd.value_or(INFINITY);
  if (!supportSd || *supportSd > limits.maxSupportSdPx * scale) {
    lose(r, "too little support: the matches fix the scene's image position only to " +
                std::to_string(r.supportSdPx) + " px (SD)");
    return finish(r);
  }
  r.message = seeded        ? "tracking from a seeded pose"
              : wasTracking ? "tracking"
                            : "initialised from the reference images";
  r.state = TrackingState::Tracking;
  state = TrackingState::Tracking;
  r.T_Ak = TAk;
  r.worldToCamera = TAk * map.T_A;
  r.covariance = est->covariance;
  if (!shiftPerReadout.empty()) {
    // The tracked frame's residuals inform the readout's estimate (used from a later frame on).
    std::vector<RollingShutterObservation> observations;
    observations.reserve(meas.threeView.size());
    for (std::size_t i = 0; i < meas.threeView.size(); ++i) {
      const ThreeViewMatch& m = meas.threeView[i];
      const Eigen::Vector3d X = TAk * m.pointA;
      observations.push_back({X, map.camera.project(X) - m.pK,
                              shiftPerReadout[static_cast<std::size_t>(threeViewCorner[i])],
                              m.sigma});
    }
    shutter->addFrame(map.camera.K()(0, 0), map.camera.K()(1, 1), observations);
  }

  // Seeds for the next frame: the inlier matches.
  prevA.clear();
  prevB.clear();
  for (std::size_t i = 0; i < mA.size(); ++i)
    if (inlierA[i]) {
      prevA.push_back({pixels[static_cast<std::size_t>(mA[i].frameCorner)], mA[i].referenceCorner});
      r.inliersA.emplace_back(
          pixels[static_cast<std::size_t>(mA[i].frameCorner)],
          refA.matchable.corners[static_cast<std::size_t>(mA[i].referenceCorner)]);
    }
  for (std::size_t i = 0; i < mB.size(); ++i)
    if (inlierB[i]) {
      prevB.push_back({pixels[static_cast<std::size_t>(mB[i].frameCorner)], mB[i].referenceCorner});
      r.inliersB.emplace_back(
          pixels[static_cast<std::size_t>(mB[i].frameCorner)],
          refB.matchable.corners[static_cast<std::size_t>(mB[i].referenceCorner)]);
    }
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
}
void PoseTracker::setMotionModel(const ArMotionModel& model) {
  model.check();
  impl_->motionModel = model;
  impl_->regularizer->setModel(model);
}
void PoseTracker::setCornerVarianceModel(const CornerVarianceModel& model) {
  model.check();
  impl_->varianceModel = model;
}
void PoseTracker::seed(const RigidPose& worldToCamera) {
  if (!worldToCamera.allFinite()) throw Error("PoseTracker::seed: non-finite pose");
  impl_->seedPose = worldToCamera;
  impl_->regularizer->reset();
}
void PoseTracker::reset() {
  impl_->seedPose.reset();
  impl_->state = TrackingState::Initialising;
  impl_->regularizer->reset();
  impl_->prevA.clear();
  impl_->prevB.clear();
}
void PoseTracker::shareRollingShutterEstimator(std::shared_ptr<RollingShutterEstimator> shared) {
  if (!shared) throw Error("PoseTracker::shareRollingShutterEstimator: null estimator");
  impl_->shutter = std::move(shared);
}
double PoseTracker::rollingShutterReadout() const { return impl_->readout(); }
const ReferenceMap& PoseTracker::map() const { return impl_->map; }
TrackingState PoseTracker::state() const { return impl_->state; }

}  // namespace reftrack
