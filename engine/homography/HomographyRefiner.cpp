#include "engine/homography/HomographyRefiner.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/RobustHomographyEstimator.hpp"
#include "engine/homography/WindowAlignment.hpp"

namespace reftrack {

namespace {

// Reference points: the strongest Harris corners down to this fraction of the strongest
// response, at least this far apart (pixels at 320x240), with no grid quota (points on
// texture only; a flat table or wall gives none).
constexpr double kPointQuality = 0.005;
constexpr double kPointSpacingPx = 4.0;
// Lucas-Kanade window half size (pixels at 320x240; 5 -> 11x11 at 640x480) and the pyramid
// levels of the first round (the start may be a few pixels off; later rounds start within a
// fraction of a pixel and run at full resolution only).
constexpr double kWindowHalfPx = 2.5;
constexpr int kFirstRoundLevels = 2;
// Cauchy scale of the fit (pixels at 320x240): matches beyond a few times this hardly count.
constexpr double kCauchyScalePx = 1.0;
// Rounds stop when H moves less than this at the frame corners (pixels), or after kMaxRounds.
constexpr double kConvergedPx = 0.01;
constexpr int kMaxRounds = 4;
constexpr int kReweightings = 4;  // Cauchy reweightings per round
// Images larger than 640x480 are aligned on the coarsest pyramid level (cv::pyrDown) that still
// holds half of its pixels: 1280x720 and 1920x1080 on their first level. Measured with
// `reftrack bench-homography` (README, HD speed): at full resolution the refinement alone cost
// more than the 3 ms a 1280x720 frame may take; on the level the error at the frame corners stays
// a few hundredths of a pixel.
constexpr double kLevelMinPixels = 640.0 * 480.0 / 2.0;

int alignmentLevel(cv::Size size) {
  int level = 0;
  for (double area = static_cast<double>(size.width) * size.height; area / 4.0 >= kLevelMinPixels;
       area /= 4.0)
    ++level;
  return level;
}

double cornerShift(const cv::Matx33d& a, const cv::Matx33d& b, cv::Size size) {
  double worst = 0;
  for (const cv::Point2d c :
       {cv::Point2d(0, 0), cv::Point2d(size.width - 1, 0), cv::Point2d(0, size.height - 1),
        cv::Point2d(size.width - 1, size.height - 1)})
    worst = std::max(worst, cv::norm(transferPoint(a, c) - transferPoint(b, c)));
  return worst;
}

bool finite(const cv::Matx33d& H) {
  for (int k = 0; k < 9; ++k)
    if (!std::isfinite(H.val[k])) return false;
  return true;
}

}  // namespace

HomographyRefiner::HomographyRefiner(const cv::Mat& referenceGray, int pointsAt320x240,
                                     bool fullResolution) {
  if (referenceGray.empty()) throw Error("homography refiner: the reference image is empty");
  if (pointsAt320x240 < 8) throw Error("homography refiner: at least 8 points are needed");
  level_ = fullResolution ? 0 : alignmentLevel(referenceGray.size());
  reference_ = ImagePyramid(toGray8(referenceGray)).level(level_);
  CornerParams c;
  c.countAt320x240 = pointsAt320x240;
  c.quality = kPointQuality;
  c.minDistancePx = kPointSpacingPx;
  c.gridColumns = 1;
  c.gridRows = 1;
  // Only points whose window lies inside the reference (outside it, the warped reference is
  // black and would pull the alignment).
  const int margin =
      static_cast<int>(std::lround(kWindowHalfPx * resolutionScale(reference_.size()))) + 2;
  for (const Corner& k : CornerDetector(c).detect(reference_)) {
    const cv::Point2f p = k.position;
    if (p.x >= margin && p.y >= margin && p.x < reference_.cols - 1 - margin &&
        p.y < reference_.rows - 1 - margin) {
      levelPoints_.push_back(p);
      // cv::pyrDown centres level pixel u on full-resolution pixel 2u.
      points_.push_back(p * static_cast<float>(1 << level_));
    }
  }
}

RefinedHomography HomographyRefiner::refine(const cv::Mat& frameGray, const cv::Matx33d& H,
                                            int minInliers, RefineStart start,
                                            const SupportRegion& support) const {
  if (frameGray.empty() || frameGray.type() != CV_8UC1)
    throw Error("homography refiner: the frame must be a non-empty 8-bit grey image");
  return refine(ImagePyramid(frameGray), H, minInliers, start, support);
}

RefinedHomography HomographyRefiner::refine(const ImagePyramid& frame, const cv::Matx33d& H,
                                            int minInliers, RefineStart start,
                                            const SupportRegion& support) const {
  if (level_ == 0) return refineOnLevel(frame.image(), H, minInliers, start, support);
  // On the pyramid level: H_level = S^-1 H S with S = diag(2^level, 2^level, 1).
  const double f = static_cast<double>(1 << level_);
  const cv::Matx33d S(f, 0, 0, 0, f, 0, 0, 0, 1), Sinv(1 / f, 0, 0, 0, 1 / f, 0, 0, 0, 1);
  RefinedHomography r =
      refineOnLevel(frame.level(level_), Sinv * H * S, minInliers, start, support.scaled(1.0 / f));
  r.H = r.success ? S * r.H * Sinv : H;
  for (cv::Point2f& p : r.inlierPoints) p *= static_cast<float>(f);
  return r;
}

RefinedHomography HomographyRefiner::refineOnLevel(const cv::Mat& frameGray, const cv::Matx33d& H,
                                                   int minInliers, RefineStart start,
                                                   const SupportRegion& support) const {
  RefinedHomography out;
  out.H = H;
  const double s = resolutionScale(frameGray.size());
  const int half = std::max(3, static_cast<int>(std::lround(kWindowHalfPx * s)));
  const double cauchy = kCauchyScalePx * s;
  const cv::Rect frameRect(0, 0, frameGray.cols, frameGray.rows);
  cv::Matx33d current = H;
  for (int round = 0; round < kMaxRounds; ++round) {
    const int levels = round == 0 && start == RefineStart::Coarse ? kFirstRoundLevels : 0;
    const int margin = (half + 2) << levels;
    // The reference points H puts inside the frame (with the LK window), and the frame region
    // they span: only that region of the reference is warped.
    std::vector<cv::Point2f> src, predicted;
    for (const cv::Point2f& p : levelPoints_) {
      const cv::Point2d q = transferPoint(current, cv::Point2d(p.x, p.y));
      if (q.x >= half && q.y >= half && q.x < frameGray.cols - 1 - half &&
          q.y < frameGray.rows - 1 - half &&
          support.contains(cv::Point2f(static_cast<float>(q.x), static_cast<float>(q.y)))) {
        src.push_back(p);
        predicted.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
      }
    }
    if (static_cast<int>(src.size()) < std::max(minInliers, 8)) return out;
    std::vector<cv::Point2f> a, b;
    if (levels == 0) {
      // Within about a pixel: the windows alone (measured 640x480, bench-homography: the whole
      // warp and the LK pyramid were ~80% of a tracked frame's time).
      const WindowAlignmentResult w = alignWindows(reference_, frameGray, current, predicted, half);
      for (size_t i = 0; i < w.status.size(); ++i)
        if (w.status[i]) {
          a.push_back(src[i]);
          b.push_back(w.found[i]);
        }
    } else {
      const cv::Rect roi = (cv::boundingRect(predicted) + cv::Size(1, 1) -
                            cv::Point(margin, margin) + cv::Size(2 * margin, 2 * margin)) &
                           frameRect;
      const cv::Matx33d shift(1, 0, -roi.x, 0, 1, -roi.y, 0, 0, 1);
      cv::Mat warped;
      cv::warpPerspective(reference_, warped, shift * current, roi.size(), cv::INTER_LINEAR,
                          cv::BORDER_CONSTANT, cv::Scalar(0));
      std::vector<cv::Point2f> from(predicted.size()), found;
      for (size_t i = 0; i < predicted.size(); ++i)
        from[i] = predicted[i] - cv::Point2f(static_cast<float>(roi.x), static_cast<float>(roi.y));
      found = from;
      std::vector<uchar> status;
      std::vector<float> error;
      cv::calcOpticalFlowPyrLK(
          warped, frameGray(roi), from, found, status, error, cv::Size(2 * half + 1, 2 * half + 1),
          levels, cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 20, 0.01),
          cv::OPTFLOW_USE_INITIAL_FLOW);
      for (size_t i = 0; i < status.size(); ++i)
        if (status[i]) {
          a.push_back(src[i]);
          b.push_back(found[i] + cv::Point2f(static_cast<float>(roi.x), static_cast<float>(roi.y)));
        }
    }
    if (static_cast<int>(a.size()) < std::max(minInliers, 8)) return out;
    // Cauchy-weighted least squares of the transfer error, started from the current H.
    std::vector<int> all(a.size());
    std::iota(all.begin(), all.end(), 0);
    std::vector<double> weights(a.size());
    cv::Matx33d fit = current;
    int inliers = 0;
    for (int k = 0; k < kReweightings; ++k) {
      inliers = 0;
      for (size_t i = 0; i < a.size(); ++i) {
        const double e = transferError(fit, a[i], b[i]);
        weights[i] = 1.0 / (1.0 + (e * e) / (cauchy * cauchy));
        inliers += e < cauchy ? 1 : 0;
      }
      fit = refineHomography(fit, a, b, all, weights);
    }
    if (!finite(fit) || inliers < minInliers) return out;
    const double moved = cornerShift(fit, current, frameGray.size());
    current = fit;
    out.points = static_cast<int>(a.size());
    out.inliers = inliers;
    out.inlierPoints.clear();
    for (size_t i = 0; i < a.size(); ++i)
      if (transferError(fit, a[i], b[i]) < cauchy) out.inlierPoints.push_back(b[i]);
    out.rounds = round + 1;
    if (moved < kConvergedPx) break;
  }
  out.success = true;
  out.H = current;
  return out;
}

}  // namespace reftrack
