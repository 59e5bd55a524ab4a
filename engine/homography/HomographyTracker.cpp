#include "engine/homography/HomographyTracker.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/WarpedWindowSearch.hpp"

namespace reftrack {

namespace {

// The rotation-only model replaces a successful general fit only when that fit rests on a thin
// strip of the reference — the SD of its inliers across their narrowest direction below this
// fraction of the image diagonal (a 30 px sliver at 320x240: SD ~9 px, 0.022) — and its RMS
// transfer error is at most kRotationRmsTolerance times the general fit's (see matchAndFit).
// Elsewhere the general fit is well determined and kept: a plane seen by a moving camera, or a
// rough K, would otherwise trade it for a rotation that fits the matches but not the rest of the
// image (measured on the hand-held postcard clip with a guessed K, without the thinness test:
// 46 of 161 frames changed, by up to 6.4 px at the frame corners).
constexpr double kThinSupportFraction = 0.04;
// A cold registration's final refinement must explain the fit's inliers about as well as the fit
// (see refine()).
constexpr double kColdRefineRmsFactor = 1.25;
constexpr double kColdRefineRmsSlackPx = 0.1;
// Off: with it, cold registrations of the shared planar clips' frames kept their RANSAC fit and
// ended 1.2-5.7 px from the tracked ones at the frame corners (HomographyTracker test of the
// clips in shuffled order), where the refinement brings them within 1 px.
constexpr bool kColdRefineStrict = false;
constexpr double kRotationRmsTolerance = 1.25;

// SD of the points across their narrowest direction (the smaller principal axis).
double narrowestSpread(const std::vector<cv::Point2f>& points, const std::vector<char>& use) {
  double n = 0, mx = 0, my = 0;
  for (size_t i = 0; i < points.size(); ++i)
    if (use[i]) {
      n += 1;
      mx += points[i].x;
      my += points[i].y;
    }
  if (n < 2) return 0.0;
  mx /= n;
  my /= n;
  double sxx = 0, syy = 0, sxy = 0;
  for (size_t i = 0; i < points.size(); ++i)
    if (use[i]) {
      const double dx = points[i].x - mx, dy = points[i].y - my;
      sxx += dx * dx;
      syy += dy * dy;
      sxy += dx * dy;
    }
  sxx /= n;
  syy /= n;
  sxy /= n;
  const double mean = 0.5 * (sxx + syy), half = 0.5 * (sxx - syy);
  return std::sqrt(std::max(0.0, mean - std::sqrt(half * half + sxy * sxy)));
}

// Milliseconds since `t`, which moves on to now (for consecutive stage timings).
double lap(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t).count();
  t = now;
  return ms;
}

// Cold registration of a frame that magnifies the reference works on the frame pyramid level
// where the reference appears at about its own scale: level l for a magnification m >= 2^(l -
// kLevelRounding), as long as the level keeps at least kMinLevelPixels. At full resolution the
// reference windows, sampled 2-4 times finer than its pixels, are blurred copies of the sharp
// frame: measured with `experiment-homography --experiment cold --max-scale 4` at 800x640,
// 6 of 74 views zoomed 1.4-4x registered 1.2-4.7 px off at the frame corners. The rounding:
// 40 views zoomed 1.5-4x (tilt <= 20 degrees) registered within 1 px: 33 at full resolution,
// 35 with rounding 0 or 0.6, 38 with 0.3.
constexpr double kLevelRounding = 0.3;
constexpr double kMinLevelPixels = 160.0 * 120.0;

// The level (0: full resolution) for a frame of `size` seeing the reference through H.
int magnificationLevel(const cv::Matx33d& H, cv::Size size) {
  const cv::Point2d centre((size.width - 1) / 2.0, (size.height - 1) / 2.0);
  const cv::Point2d r = transferPoint(H.inv(), centre);
  if (!std::isfinite(r.x) || !std::isfinite(r.y)) return 0;
  const cv::Matx22f J = transferJacobian(H, r);
  const double m = std::sqrt(
      std::abs(static_cast<double>(J(0, 0)) * J(1, 1) - static_cast<double>(J(0, 1)) * J(1, 0)));
  if (!(m > 0) || !std::isfinite(m)) return 0;
  int level = std::max(0, static_cast<int>(std::floor(std::log2(m) + kLevelRounding)));
  while (level > 0 && static_cast<double>(size.area()) / std::pow(4.0, level) < kMinLevelPixels)
    --level;
  return level;
}

// A registration carried from the previous frame's that moves the frame's corners farther than
// this (pixels at 320x240) from where the previous one put them is checked like a cold one: a
// video moves a few pixels between frames, photos of a folder may jump by any amount.
constexpr double kCheckedJumpPx = 10.0;

// The largest distance between where `a` and `b` (reference -> frame) put the reference points
// seen at the frame's corners (through b's inverse).
double largestShift(const cv::Matx33d& a, const cv::Matx33d& b, cv::Size size) {
  const cv::Matx33d binv = b.inv();
  double worst = 0;
  for (const cv::Point2d c :
       {cv::Point2d(0, 0), cv::Point2d(size.width - 1, 0), cv::Point2d(0, size.height - 1),
        cv::Point2d(size.width - 1, size.height - 1)}) {
    const cv::Point2d q = transferPoint(a, transferPoint(binv, c));
    const double d = std::hypot(q.x - c.x, q.y - c.y);
    worst = std::max(worst, std::isfinite(d) ? d : std::numeric_limits<double>::infinity());
  }
  return worst;
}

}  // namespace

namespace {

const TrackerParams& checked(const TrackerParams& p) {
  p.check();
  return p;
}

// The tracker applies the 35% rule to the reference corners the frame can see (the paper's
// test), not to the correlation matches: unguided whole-image matching of a barely overlapping
// frame yields many more false matches than visible corners.
RansacParams frameFitParams(const RansacParams& p) {
  RansacParams r = p;
  r.minInlierRatio = 0.0;
  return r;
}

// The corner parameters with the count scaled by `factor`.
CornerParams scaledCount(const CornerParams& corners, double factor) {
  CornerParams c = corners;
  c.countAt320x240 = static_cast<int>(std::lround(c.countAt320x240 * factor));
  return c;
}

// The re-acquisition corner parameters: denser, weaker and closer than the tracking corners.
// Above 320x240 the count is not scaled up with the image area: unguided matching compares
// every pair, so its cost grows with the square of the count (measured cold registration at
// 640x480 with the area-scaled 1760 corners: 37-46 ms per frame).
CornerParams reacquisitionCorners(const TrackerParams& p, cv::Size imageSize) {
  const double area = countScale(imageSize);  // what CornerParams::countFor multiplies by
  CornerParams c = scaledCount(p.corners, p.homography.reacquireCornerFactor / std::max(1.0, area));
  c.countAt320x240 = std::max(c.countAt320x240, p.corners.countAt320x240);
  c.quality = std::min(c.quality, p.homography.reacquireCornerQuality);
  c.minDistancePx = std::min(c.minDistancePx, p.homography.reacquireMinDistancePx);
  return c;
}

}  // namespace

HomographyTracker::ReferenceSet HomographyTracker::referenceSet(const cv::Mat& gray,
                                                                const CornerDetector& detector,
                                                                int halfWindow) {
  ReferenceSet r{detector.detect(gray), {}, NccPatches(halfWindow)};
  r.points = positionsOf(r.corners);
  r.patches = NccPatches::square(gray, r.points, halfWindow);
  return r;
}

HomographyTracker::HomographyTracker(const cv::Mat& reference, const TrackerParams& params,
                                     const std::optional<Eigen::Matrix3d>& K)
    : params_(checked(params)),
      detector_(params_.corners),
      frameDetector_(scaledCount(params_.corners, params_.homography.frameCornerFactor)),
      reacquireDetector_(reacquisitionCorners(params_, reference.size())),
      frameReacquireDetector_(reacquisitionCorners(params_, reference.size())),
      frameSize_(reference.size()),
      matcher_(params.correlation),
      estimator_(frameFitParams(params_.ransac)),
      prevPatches_(params.correlation.halfWindow) {
  if (reference.empty()) throw Error("homography tracker: the reference image is empty");
  if (K && params_.homography.rotationModel)
    rotationEstimator_.emplace(*K, frameFitParams(params_.ransac));
  refGray_ = toGray8(reference).clone();
  const int half = params_.correlation.halfWindow;
  ref_ = referenceSet(refGray_, detector_, half);
  if (ref_.corners.size() < 8)
    throw Error("homography tracker: only " + std::to_string(ref_.corners.size()) +
                " corners in the reference image (at least 8 needed; is it textured?)");
  reacquireRef_ = referenceSet(refGray_, reacquireDetector_, half);
  if (params_.homography.keypoints != KeypointLayer::None)
    keypointRegistrar_.emplace(refGray_, params_.homography, params_.ransac);
  if (params_.homography.refinePoints > 0)
    refiner_.emplace(refGray_, params_.homography.refinePoints);
  if (params_.homography.verify)
    verifier_.emplace(refGray_, RegistrationCheckParams::from(params_.homography));
}

void HomographyTracker::reset() {
  lastH_.reset();
  coastH_.reset();
  prevPoints_.clear();
}

std::optional<cv::Matx33d> HomographyTracker::predict(const cv::Matx33d& base, bool coasting,
                                                      const std::vector<cv::Point2f>& points,
                                                      const NccPatches& patches,
                                                      cv::Size frameSize) const {
  if (!params_.homography.frameToFramePrediction || prevPoints_.empty()) return base;
  const double s = resolutionScale(frameSize);
  const std::vector<CornerMatch> m = matcher_.match(prevPoints_, prevPatches_, points, patches,
                                                    params_.correlation.searchHalfWidthPx * s,
                                                    params_.correlation.searchHalfHeightPx * s);
  std::vector<cv::Point2f> a, b;
  std::vector<float> score;
  for (const CornerMatch& c : m) {
    a.push_back(prevPoints_[static_cast<size_t>(c.first)]);
    b.push_back(points[static_cast<size_t>(c.second)]);
    score.push_back(c.score);
  }
  RansacParams rp = params_.ransac;
  rp.refine = false;  // the prediction only needs to land within the guided search window
  const HomographyEstimate f2f = RobustHomographyEstimator(rp).estimate(a, b, frameSize, score);
  // Without a frame-to-frame homography a coasted registration has nothing left to carry it.
  if (!f2f.success) return coasting ? std::nullopt : std::optional<cv::Matx33d>(base);
  return f2f.H * base;
}

HomographyTracker::Attempt HomographyTracker::attempt(
    const ImagePyramid& frame, const CornerDetector& detector, const ReferenceSet& ref,
    const std::optional<cv::Matx33d>& base, bool coasting, double stageMs[kStages],
    bool chainFrameToFrame, int denseRadius, const SupportRegion& support) {
  const cv::Mat& gray = frame.image();
  Attempt a;
  auto clock = std::chrono::steady_clock::now();
  a.points = positionsOf(detector.detect(frame));
  a.patches = NccPatches::square(gray, a.points, params_.correlation.halfWindow);
  stageMs[0] += lap(clock);

  if (base)
    a.prediction =
        chainFrameToFrame ? predict(*base, coasting, a.points, a.patches, gray.size()) : base;
  stageMs[1] += lap(clock);
  const double guidedHalf =
      params_.homography.guidedSearchHalfSizePx * resolutionScale(gray.size());
  matchAndFit(a, gray, ref, a.prediction, guidedHalf, stageMs, denseRadius, support);
  // Unguided, the whole-image search's mutual-best rule loses true matches to look-alikes far
  // away; a hypothesis that falls short of the inlier rules is checked once more by matching
  // around the positions it predicts (guided matching, Hartley & Zisserman Alg. 4.6). Measured
  // on the rotation sweep at 640x480, 30 degrees: 87% of 100 trials registered without it.
  if (!a.prediction && !a.tracked && a.hypothesis) {
    Attempt unguided = a;
    const cv::Matx33d hypothesis = *a.hypothesis;
    matchAndFit(a, gray, ref, hypothesis, guidedHalf, stageMs);
    if (!a.tracked) a = std::move(unguided);
  }
  return a;
}

void HomographyTracker::matchAndFit(Attempt& a, const cv::Mat& gray, const ReferenceSet& ref,
                                    const std::optional<cv::Matx33d>& guide, double guidedHalf,
                                    double stageMs[kStages], int denseRadius,
                                    const SupportRegion& support) const {
  auto clock = std::chrono::steady_clock::now();
  a.src.clear();
  a.dst.clear();
  a.est = {};
  a.hypothesis.reset();
  a.inlierRatio = 0.0;
  a.rotationModel = false;
  a.tracked = false;
  a.failure.clear();
  std::vector<CornerMatch> matches;
  // Dense search (denseRadius > 0): (reference, frame) positions and their NCC.
  std::vector<std::pair<cv::Point2f, cv::Point2f>> windowMatches;
  std::vector<float> windowScores;
  const double s = resolutionScale(gray.size());
  // Reference corners whose correlation window can be formed (else they cannot be matched).
  std::vector<char> measurable(ref.points.size(), 1);
  if (guide) {
    // Reference windows warped into this frame's geometry: window pixel m around the predicted
    // position q maps to the reference at r + J m, J the Jacobian of H_pred^-1 at q.
    const cv::Matx33d Hinv = guide->inv();
    std::vector<cv::Matx22f> maps(ref.points.size());
    // A reference corner predicted farther outside the frame than any search reaches gets no
    // window (a NaN map: NccPatches::warped marks it invalid without sampling): it can have no
    // candidate, and the failure test below counts only corners mapped inside the frame. On a
    // pan most of the reference can lie outside the view.
    const double reach = std::max(guidedHalf, static_cast<double>(denseRadius)) +
                         2.0 * params_.correlation.halfWindow + 2.0;
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (size_t i = 0; i < ref.points.size(); ++i) {
      const cv::Point2d q = transferPoint(*guide, cv::Point2d(ref.points[i].x, ref.points[i].y));
      const bool reachable =
          q.x > -reach && q.y > -reach && q.x < gray.cols + reach && q.y < gray.rows + reach;
      maps[i] =
          reachable ? cv::Matx22f(transferJacobian(Hinv, q)) : cv::Matx22f(nan, nan, nan, nan);
    }
    const NccPatches warpedRef =
        NccPatches::warped(refGray_, ref.points, maps, params_.correlation.halfWindow);
    for (size_t i = 0; i < ref.points.size(); ++i)
      measurable[i] = warpedRef.valid(static_cast<int>(i)) ? 1 : 0;
    if (denseRadius > 0) {
      std::vector<cv::Point2f> predicted(ref.points.size());
      for (size_t i = 0; i < ref.points.size(); ++i) {
        const cv::Point2d q = transferPoint(*guide, cv::Point2d(ref.points[i].x, ref.points[i].y));
        predicted[i] = cv::Point2f(static_cast<float>(q.x), static_cast<float>(q.y));
      }
      for (const WindowMatch& w : searchWarpedWindows(gray, warpedRef, predicted, denseRadius,
                                                      params_.correlation.minScore)) {
        windowMatches.push_back({ref.points[static_cast<size_t>(w.reference)], w.position});
        windowScores.push_back(w.score);
      }
    } else {
      matches =
          matcher_.match(ref.points, warpedRef, a.points, a.patches, guidedHalf, guidedHalf, guide);
    }
  } else {
    const double hw = params_.homography.reacquireWholeImage
                          ? gray.cols
                          : params_.correlation.searchHalfWidthPx * s;
    const double hh = params_.homography.reacquireWholeImage
                          ? gray.rows
                          : params_.correlation.searchHalfHeightPx * s;
    for (size_t i = 0; i < ref.points.size(); ++i)
      measurable[i] = ref.patches.valid(static_cast<int>(i)) ? 1 : 0;
    matches = matcher_.match(ref.points, ref.patches, a.points, a.patches, hw, hh);
  }
  a.matches = static_cast<int>(matches.size() + windowMatches.size());
  stageMs[2] += lap(clock);

  a.src.reserve(static_cast<size_t>(a.matches));
  a.dst.reserve(static_cast<size_t>(a.matches));
  std::vector<float> score;
  score.reserve(static_cast<size_t>(a.matches));
  for (const CornerMatch& m : matches) {
    a.src.push_back(ref.points[static_cast<size_t>(m.first)]);
    a.dst.push_back(a.points[static_cast<size_t>(m.second)]);
    score.push_back(m.score);
  }
  for (size_t i = 0; i < windowMatches.size(); ++i) {
    a.src.push_back(windowMatches[i].first);
    a.dst.push_back(windowMatches[i].second);
    score.push_back(windowScores[i]);
  }
  // The paper's failure test: inliers among the reference corners this frame can see (mapped
  // inside it with their whole window, and with a window in the reference).
  const int margin = params_.correlation.halfWindow;
  const auto judge = [&](const HomographyEstimate& est, double& ratio, std::string& failure) {
    if (!est.success) {
      failure = est.failure;
      return false;
    }
    int visible = 0;
    for (size_t i = 0; i < ref.points.size(); ++i) {
      if (!measurable[i]) continue;
      const cv::Point2d q = transferPoint(est.H, cv::Point2d(ref.points[i].x, ref.points[i].y));
      if (q.x >= margin && q.y >= margin && q.x < gray.cols - margin && q.y < gray.rows - margin &&
          support.contains(cv::Point2f(static_cast<float>(q.x), static_cast<float>(q.y))))
        ++visible;
    }
    ratio = static_cast<double>(est.inlierCount) / std::max(visible, est.inlierCount);
    if (ratio < params_.ransac.minInlierRatio) {
      failure = "only " + std::to_string(est.inlierCount) + " of " + std::to_string(visible) +
                " visible reference corners are inliers" +
                (support.whole() ? "" : " (in the keypoint inliers' region)");
      return false;
    }
    return true;
  };
  if (!windowMatches.empty()) {
    // Fitted as the correction of the prediction (predicted -> found positions, near the
    // identity) and chained with it: the determinant test then judges the correction, not the
    // view (a 2x zoom seen at 45 degrees has |det H| > 20 at the reference's origin).
    std::vector<cv::Point2f> predictedSrc;
    predictedSrc.reserve(a.src.size());
    for (const cv::Point2f& r : a.src) {
      const cv::Point2d q = transferPoint(*guide, cv::Point2d(r.x, r.y));
      predictedSrc.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
    }
    a.est = estimator_.estimate(predictedSrc, a.dst, gray.size(), score);
    if (a.est.success) {
      a.est.H = a.est.H * *guide;
      a.est.H *= 1.0 / a.est.H(2, 2);
    }
  } else {
    // Samples spread over the reference (src), inlier distances in the frame (dst).
    a.est = estimator_.estimate(a.src, a.dst, refGray_.size(), score, gray.size());
  }
  a.tracked = judge(a.est, a.inlierRatio, a.failure);
  if (a.est.success) a.hypothesis = a.est.H;
  // The rotation-only model when the general one fails, and in its place when it explains the
  // matches as well (the simpler model: a general H fitted to a sliver of overlap is pinned down
  // only along it; measured on a 0.5 degree-per-frame pan at 29.5-31 degrees, 320x240: general
  // H 1.5-1.7 px annotation error where the rotation model gives < 0.5). A registered frame
  // whose inliers are not a thin strip (kThinSupportFraction) keeps the general fit, so the
  // rotation model is not even estimated there (most tracked frames).
  const bool thin =
      a.est.success && narrowestSpread(a.src, a.est.inliers) <
                           kThinSupportFraction * std::hypot(refGray_.cols, refGray_.rows);
  // K is the frames' camera: the rotation-only model holds only for a reference of their size,
  // which is then taken to come from the same camera.
  if (rotationEstimator_ && gray.size() == refGray_.size() && (!a.tracked || thin)) {
    HomographyEstimate rot = rotationEstimator_->estimate(a.src, a.dst, gray.size(), score);
    // "As well": as many inliers and a transfer error on them hardly above the general fit's
    // (which has 5 more parameters to absorb noise with).
    const bool asGood = thin && rot.inlierCount >= a.est.inlierCount &&
                        rot.rmsTransferError <= kRotationRmsTolerance * a.est.rmsTransferError;
    if (rot.success && (!a.est.success || rot.inlierCount >= a.est.inlierCount))
      a.hypothesis = rot.H;
    if (rot.success && (!a.tracked || asGood)) {
      double ratio = 0.0;
      std::string failure;
      if (judge(rot, ratio, failure)) {
        a.est = std::move(rot);
        a.inlierRatio = ratio;
        a.failure.clear();
        a.rotationModel = true;
        a.tracked = true;
      } else if (!a.tracked) {
        a.failure += "; rotation model: " + failure;
      }
    } else if (!a.tracked) {
      a.failure += "; rotation model: " + rot.failure;
    }
  }
  stageMs[3] += lap(clock);
}

SupportRegion HomographyTracker::supportOf(const Attempt& a, cv::Size frameSize) const {
  std::vector<cv::Point2f> points;
  for (size_t i = 0; i < a.dst.size() && i < a.est.inliers.size(); ++i)
    if (a.est.inliers[i]) points.push_back(a.dst[i]);
  if (points.empty()) points = a.alignedInliers;
  return SupportRegion(points, supportMargin(frameSize));
}

void HomographyTracker::refine(Attempt& a, const ImagePyramid& frame, double stageMs[kStages],
                               const HomographyRefiner* refiner,
                               const SupportRegion& support) const {
  const cv::Mat& gray = frame.image();
  auto clock = std::chrono::steady_clock::now();
  const RefinedHomography r =
      (refiner ? *refiner : *refiner_)
          .refine(frame, a.est.H, params_.ransac.minInliers, RefineStart::Close, support);
  // Kept only where it agrees with the fit it started from: its transfer error on that fit's
  // inliers within the inlier threshold (RMS), so a refinement that slid off cannot replace it.
  // A cold registration (given its inliers' region) keeps it only where it explains those
  // inliers about as well as the fit does (RMS at most kColdRefineRmsFactor times the fit's,
  // plus kColdRefineRmsSlackPx at 320x240): on a view that is only partly the plane, the
  // refinement's Cauchy fit over every textured point of the region settles between the plane
  // and what stands before or behind it, where the RANSAC fit keeps to the plane (measured on
  // the real pairs: BruggeTower 1.1 -> 3.0 px over the overlap, Eiffel 0.8 -> 2.2 px).
  if (r.success) {
    const double s = resolutionScale(gray.size());
    double threshold = params_.ransac.inlierThresholdPx * s;
    double sq = 0, fitSq = 0;
    int n = 0;
    for (size_t i = 0; i < a.src.size(); ++i)
      if (a.est.inliers[i]) {
        const double e = transferError(r.H, a.src[i], a.dst[i]);
        const double f = transferError(a.est.H, a.src[i], a.dst[i]);
        sq += e * e;
        fitSq += f * f;
        ++n;
      }
    if (n > 0 && !support.whole() && kColdRefineStrict)
      threshold = std::min(threshold,
                           kColdRefineRmsFactor * std::sqrt(fitSq / n) + kColdRefineRmsSlackPx * s);
    if (n > 0 && std::sqrt(sq / n) <= threshold) a.est.H = r.H;
  }
  stageMs[5] += lap(clock);
}

const HomographyRefiner& HomographyTracker::levelRefiner(int level) {
  auto it = levelRefiners_.find(level);
  if (it == levelRefiners_.end())
    it = levelRefiners_
             .emplace(level,
                      HomographyRefiner(refGray_,
                                        params_.homography.refinePoints * (1 << (2 * level)), true))
             .first;
  return it->second;
}

void HomographyTracker::finish(Attempt& a, const ImagePyramid& frame,
                               double stageMs[kStages]) const {
  if (!a.tracked || a.finished) return;
  a.finished = true;
  // Checked where H is known to hold: its inliers' region of the frame.
  const SupportRegion support = supportOf(a, frame.image().size());
  // The refinement itself aligns the whole frame: kept to the inliers' region, cold registrations
  // of the shared planar clips' frames ended 1.2-5.7 px from the tracked ones at the frame
  // corners (HomographyTracker test of the clips in shuffled order), where it brings them within
  // 1 px.
  if (refiner_ && !a.rotationModel && a.level == 0) refine(a, frame, stageMs);
  if (!verifier_) return;
  auto clock = std::chrono::steady_clock::now();
  const RegistrationCheck c = verifier_->check(frame, a.est.H, support);
  stageMs[6] += lap(clock);
  a.check = c.summary();
  if (!c.passed) {
    a.tracked = false;
    a.failure = "refused by the registration check: " + c.failure + " (" + c.summary() + ")";
  }
}

HomographyTracker::Attempt HomographyTracker::alignedAttempt(
    const ImagePyramid& frame, const cv::Matx33d& start, double stageMs[kStages],
    const std::vector<cv::Point2f>& startInliers) {
  const cv::Mat& gray = frame.image();
  // A frame that magnifies the reference is registered on the pyramid level where the
  // reference appears at about its own scale, then carried back exactly.
  const int level = magnificationLevel(start, gray.size());
  std::optional<ImagePyramid> levelPyramid;
  if (level > 0) levelPyramid.emplace(frame.level(level));
  const ImagePyramid& work = levelPyramid ? *levelPyramid : frame;
  const cv::Matx33d S = ImagePyramid::levelToImage(level),
                    Sinv = ImagePyramid::levelToImage(level).inv();
  // The start predicts; the reference corners matched around it with warped windows give the
  // result (the tracking set, then the denser one, as while tracking).
  const int radius =
      std::max(2, static_cast<int>(std::lround(params_.homography.keypointSearchHalfSizePx *
                                               resolutionScale(work.image().size()))));
  // The start (a keypoint homography: 1-3 px off at the frame corners) is first refined by the
  // refiner's alignment, which warps the reference exactly (the windows' affine warp is only
  // exact at their centres: at 45-50 degrees of tilt the guided windows then miss).
  cv::Matx33d guide = Sinv * start;
  const HomographyRefiner* refiner = !refiner_   ? nullptr
                                     : level > 0 ? &levelRefiner(level)
                                                 : &*refiner_;
  // The start's inliers' region, on the level worked on (the whole frame without them).
  const SupportRegion startSupport =
      startInliers.empty()
          ? SupportRegion()
          : SupportRegion(startInliers, supportMargin(gray.size())).scaled(1.0 / (1 << level));
  RefinedHomography aligned;
  if (refiner) {
    auto refineClock = std::chrono::steady_clock::now();
    // Over the whole frame: the start's inliers may lie on another surface than the one most
    // of the view follows (measured on a city seen from a tower, BruggeTower of the real
    // pairs: aligned within the keypoint inliers' hull 8.5 px off over the overlap, over the
    // whole frame 3.3 px, its corner fit 1.1 px).
    aligned = refiner->refine(work, guide, params_.ransac.minInliers);
    if (aligned.success) guide = aligned.H;
    stageMs[5] += lap(refineClock);
  }
  Attempt a =
      attempt(work, frameDetector_, ref_, guide, false, stageMs, false, radius, startSupport);
  if (!a.tracked) {
    Attempt dense = attempt(work, frameReacquireDetector_, reacquireRef_, guide, false, stageMs,
                            false, radius, startSupport);
    if (dense.tracked) a = std::move(dense);
  }
  if (!a.tracked && aligned.success &&
      aligned.inliers >=
          std::max(params_.ransac.minInliers,
                   static_cast<int>(params_.ransac.minInlierRatio * aligned.points))) {
    // The corners fail where the frame has lost them (a strong blur: Oxford trees 1->6 keeps 44
    // of 284 reference corners) while the whole-image alignment still holds: its H stands, to
    // be confirmed by the registration check like any cold one.
    a.est.success = true;
    a.est.H = aligned.H;
    a.est.inlierCount = aligned.inliers;
    a.inlierRatio = static_cast<double>(aligned.inliers) / aligned.points;
    a.failure.clear();
    a.src.clear();
    a.dst.clear();
    a.est.inliers.clear();
    a.alignedInliers = aligned.inlierPoints;
    a.tracked = true;
  }
  if (a.tracked && level > 0) {
    // The final refinement on the level too, then everything in full-resolution pixels.
    if (refiner) refine(a, work, stageMs, refiner, supportOf(a, work.image().size()));
    a.level = level;
    a.est.H = S * a.est.H;
    a.est.H *= 1.0 / a.est.H(2, 2);
    if (a.prediction) a.prediction = S * *a.prediction;
    if (a.hypothesis) a.hypothesis = S * *a.hypothesis;
    const auto lift = [&](std::vector<cv::Point2f>& points) {
      for (cv::Point2f& p : points) p *= static_cast<float>(1 << level);
    };
    lift(a.points);
    lift(a.dst);
    lift(a.alignedInliers);
  }
  finish(a, frame, stageMs);
  return a;
}

HomographyTracker::Attempt HomographyTracker::coldAttempt(const ImagePyramid& frame,
                                                          double stageMs[kStages],
                                                          bool& keypointGuided) {
  const cv::Mat& gray = frame.image();
  keypointGuided = false;
  std::string keypointFailure;
  if (keypointRegistrar_) {
    auto clock = std::chrono::steady_clock::now();
    const KeypointRegistration k = keypointRegistrar_->registerFrame(gray);
    stageMs[4] += lap(clock);
    if (k.found) {
      Attempt a = alignedAttempt(frame, k.H, stageMs, k.inlierPoints);
      if (a.tracked) {
        keypointGuided = true;
        return a;
      }
      keypointFailure = "around the keypoint homography: " + a.failure;
    } else {
      keypointFailure = "keypoints: " + k.failure;
    }
  }
  Attempt a = attempt(frame, frameReacquireDetector_, reacquireRef_, std::nullopt, false, stageMs);
  finish(a, frame, stageMs);
  if (!a.tracked && !keypointFailure.empty())
    a.failure = keypointFailure + "; unguided: " + a.failure;
  return a;
}

HomographyTrackResult HomographyTracker::track(const cv::Mat& frame) {
  if (frame.empty()) throw Error("homography tracker: the frame is empty");
  const cv::Mat gray = toGray8(frame);
  // A frame of another size than the last one comes from another source: nothing of the last
  // frame predicts it. The re-acquisition detector's count is set for the frame's size.
  if (gray.size() != frameSize_) {
    reset();
    frameSize_ = gray.size();
    frameReacquireDetector_ = CornerDetector(reacquisitionCorners(params_, frameSize_));
  }
  const ImagePyramid pyramid(gray);  // its levels are shared by the corners and the refinement
  double stageMs[kStages] = {0, 0, 0, 0, 0, 0, 0};
  bool keypointGuided = false;
  // While tracking (or coasting after a loss): the reference's corners matched around their
  // predicted positions in the denser frame set. Unguided, with the denser re-acquisition sets
  // on both sides: when there is no prediction, or when the coasted one failed too.
  const bool coasting = !lastH_.has_value();
  const std::optional<cv::Matx33d> base = lastH_ ? lastH_ : coastH_;
  Attempt a;
  if (base) a = attempt(pyramid, frameDetector_, ref_, base, coasting, stageMs);
  if (!a.tracked && a.prediction) {
    // A frame that shares only a sliver with the reference holds few of the tracking corners:
    // the denser re-acquisition sets are matched around the same prediction (measured on a
    // 0.5 degree-per-frame pan, 33 degree view, 320x240: without this, every other frame from
    // 22 degrees on was lost, its successor re-acquired unguided).
    Attempt dense = attempt(pyramid, frameReacquireDetector_, reacquireRef_, a.prediction, coasting,
                            stageMs, false);
    if (dense.tracked) a = std::move(dense);
  }
  // After a loss, a registration guided by the coasted prediction is checked like a cold one.
  if (coasting) finish(a, pyramid, stageMs);
  if (!a.tracked && a.prediction && !coasting) {
    // The corner matching around the prediction failed: on a repeated pattern (bricks, tiles)
    // a unit's corners have look-alikes within the guided search window. The prediction is
    // aligned first (the refiner's Lucas-Kanade converges to the nearest match, a fraction of
    // a unit away) and the reference windows searched close around it, as for a cold frame;
    // the result is checked like one.
    Attempt aligned = alignedAttempt(pyramid, *a.prediction, stageMs);
    if (aligned.tracked) {
      a = std::move(aligned);
    } else {
      a.failure += "; aligned: " + aligned.failure;
    }
  }
  std::optional<cv::Matx33d> coastNext;
  std::string guidedFailure;  // why the guided attempt (if any) failed
  bool cold = false;          // a cold attempt followed it
  if (!a.tracked) {
    coastNext = a.prediction;
    if (a.prediction)
      guidedFailure =
          (coasting ? "coasted prediction: " : "guided by the previous frame: ") + a.failure;
    else if (base)
      guidedFailure = "coasting ended: no frame-to-frame homography";
    // The frame is registered cold too, including the first one the tracking loses: a sequence
    // of photos (an image folder) may jump from view to view (measured on the simulated brick
    // wall's 40 and 50 degree views in a row: lost guided, registered cold). The guided
    // attempt's frame corners seed the next frame-to-frame homography only if the cold attempt
    // does not replace them.
    prevPoints_ = std::move(a.points);
    prevPatches_ = std::move(a.patches);
    a = coldAttempt(pyramid, stageMs, keypointGuided);
    cold = true;
  }

  // Tracked from the previous frame: refined (cold and coasted ones were finished), and checked
  // only when it jumped far from the previous frame's registration (photos of an image folder,
  // not a video: a guided match across a large jump can lock onto a wrong one).
  if (a.tracked && !a.finished) {
    if (refiner_ && !a.rotationModel) refine(a, pyramid, stageMs);
    if (verifier_ && lastH_ &&
        largestShift(*lastH_, a.est.H, gray.size()) >
            kCheckedJumpPx * resolutionScale(gray.size())) {
      auto clock = std::chrono::steady_clock::now();
      const RegistrationCheck c =
          verifier_->check(pyramid, a.est.H, supportOf(a, pyramid.image().size()));
      stageMs[6] += lap(clock);
      a.check = c.summary();
      if (!c.passed) {
        a.tracked = false;
        a.failure =
            "guided by the previous frame, then refused by the registration check: " + c.failure +
            " (" + c.summary() + ")";
      }
    }
  }

  HomographyTrackResult out;
  out.tracked = a.tracked;
  out.guided = a.prediction.has_value() && !keypointGuided;
  out.keypointGuided = keypointGuided;
  out.rotationModel = a.rotationModel;
  out.check = a.check;
  out.corners = static_cast<int>(a.points.size());
  out.matches = a.matches;
  out.inliers = a.est.inlierCount;
  out.inlierRatio = a.inlierRatio;
  // Why a lost frame is lost (every one gets a reason): too few corners first (black,
  // textureless or blurred), else the attempts made, in order.
  if (!a.tracked) {
    const int needed = std::max(4, params_.ransac.minInliers);
    if (static_cast<int>(a.points.size()) < needed)
      out.failure = "too few corners (" + std::to_string(a.points.size()) +
                    "): textureless, black or blurred frame";
    else if (cold)
      out.failure = (guidedFailure.empty() ? "" : guidedFailure + "; ") + "cold: " + a.failure;
    else
      out.failure = guidedFailure;
  }
  if (a.est.success) out.H = a.est.H;
  for (size_t i = 0; i < a.src.size(); ++i)
    if (a.est.inliers[i]) out.inlierMatches.emplace_back(a.src[i], a.dst[i]);
  out.frameCorners = a.points;
  const char* names[kStages] = {"corners",   "prediction", "matching", "robust fit",
                                "keypoints", "refine",     "verify"};
  for (int i = 0; i < kStages; ++i) out.stageMs.emplace_back(names[i], stageMs[i]);
  prevPoints_ = std::move(a.points);
  prevPatches_ = std::move(a.patches);
  // Windows of a pyramid level do not match the next frame's: it is predicted by H alone.
  if (a.level > 0) prevPoints_.clear();
  if (a.tracked) {
    lastH_ = a.est.H;
    coastH_.reset();
  } else {
    lastH_.reset();
    coastH_ = coastNext;
  }
  return out;
}

Eigen::Matrix3d rotationFromHomography(const cv::Matx33d& H, const Eigen::Matrix3d& K) {
  Eigen::Matrix3d He;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) He(r, c) = H(r, c);
  Eigen::Matrix3d M = K.inverse() * He * K;
  const double det = M.determinant();
  if (!std::isfinite(det) || std::abs(det) < 1e-300)
    throw Error("rotation from homography: H is singular");
  M /= std::cbrt(det);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  if (R.determinant() < 0) {
    Eigen::Matrix3d U = svd.matrixU();
    U.col(2) *= -1;
    R = U * svd.matrixV().transpose();
  }
  return R;
}

}  // namespace reftrack
