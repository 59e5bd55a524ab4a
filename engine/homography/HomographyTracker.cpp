#include "engine/homography/HomographyTracker.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <chrono>
#include <cmath>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/homography/HomographyDlt.hpp"

namespace reftrack {

namespace {

// Jacobian of the map p -> H p (dehomogenised) at p.
cv::Matx22f jacobianAt(const cv::Matx33d& H, cv::Point2d p) {
  const double w = H(2, 0) * p.x + H(2, 1) * p.y + H(2, 2);
  const double u = (H(0, 0) * p.x + H(0, 1) * p.y + H(0, 2)) / w;
  const double v = (H(1, 0) * p.x + H(1, 1) * p.y + H(1, 2)) / w;
  return cv::Matx22f(static_cast<float>((H(0, 0) - u * H(2, 0)) / w),
                     static_cast<float>((H(0, 1) - u * H(2, 1)) / w),
                     static_cast<float>((H(1, 0) - v * H(2, 0)) / w),
                     static_cast<float>((H(1, 1) - v * H(2, 1)) / w));
}

// Milliseconds since `t`, which moves on to now (for consecutive stage timings).
double lap(std::chrono::steady_clock::time_point& t) {
  const auto now = std::chrono::steady_clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t).count();
  t = now;
  return ms;
}

}  // namespace

HomographyTracker::HomographyTracker(const cv::Mat& reference, const TrackerParams& params)
    : params_(params),
      detector_(params.corners),
      matcher_(params.correlation),
      estimator_(params.ransac),
      refPatches_(params.correlation.halfWindow),
      prevPatches_(params.correlation.halfWindow) {
  params_.check();
  if (reference.empty()) throw Error("homography tracker: the reference image is empty");
  refGray_ = toGray8(reference).clone();
  refCorners_ = detector_.detect(refGray_);
  if (refCorners_.size() < 8)
    throw Error("homography tracker: only " + std::to_string(refCorners_.size()) +
                " corners in the reference image (at least 8 needed; is it textured?)");
  refPoints_ = positionsOf(refCorners_);
  refPatches_ = NccPatches::square(refGray_, refPoints_, params_.correlation.halfWindow);
}

void HomographyTracker::reset() {
  lastH_.reset();
  prevPoints_.clear();
}

std::optional<cv::Matx33d> HomographyTracker::predict(const std::vector<cv::Point2f>& points,
                                                      const NccPatches& patches) const {
  if (!lastH_) return std::nullopt;
  if (!params_.homography.frameToFramePrediction || prevPoints_.empty()) return lastH_;
  const double s = resolutionScale(refGray_.size());
  const std::vector<CornerMatch> m = matcher_.match(prevPoints_, prevPatches_, points, patches,
                                                    params_.correlation.searchHalfWidthPx * s,
                                                    params_.correlation.searchHalfHeightPx * s);
  std::vector<cv::Point2f> a, b;
  for (const CornerMatch& c : m) {
    a.push_back(prevPoints_[static_cast<size_t>(c.first)]);
    b.push_back(points[static_cast<size_t>(c.second)]);
  }
  RansacParams rp = params_.ransac;
  rp.refine = false;  // the prediction only needs to land within the guided search window
  const HomographyEstimate f2f = RobustHomographyEstimator(rp).estimate(a, b, refGray_.size());
  if (!f2f.success) return lastH_;
  return f2f.H * *lastH_;
}

HomographyTrackResult HomographyTracker::track(const cv::Mat& frame) {
  HomographyTrackResult out;
  auto clock = std::chrono::steady_clock::now();
  const cv::Mat gray = toGray8(frame);
  if (gray.size() != refGray_.size())
    throw Error("homography tracker: frame is " + std::to_string(gray.cols) + "x" +
                std::to_string(gray.rows) + " but the reference is " +
                std::to_string(refGray_.cols) + "x" + std::to_string(refGray_.rows));
  const std::vector<Corner> corners = detector_.detect(gray);
  out.corners = static_cast<int>(corners.size());
  std::vector<cv::Point2f> points = positionsOf(corners);
  NccPatches patches = NccPatches::square(gray, points, params_.correlation.halfWindow);
  out.stageMs.emplace_back("corners", lap(clock));

  const std::optional<cv::Matx33d> prediction = predict(points, patches);
  out.stageMs.emplace_back("prediction", lap(clock));
  std::vector<CornerMatch> matches;
  const double s = resolutionScale(gray.size());
  if (prediction) {
    // Reference windows warped into this frame's geometry: window pixel m around the predicted
    // position q maps to the reference at r + J m, J the Jacobian of H_pred^-1 at q.
    const cv::Matx33d Hinv = prediction->inv();
    std::vector<cv::Matx22f> maps(refPoints_.size());
    for (size_t i = 0; i < refPoints_.size(); ++i) {
      const cv::Point2d q =
          transferPoint(*prediction, cv::Point2d(refPoints_[i].x, refPoints_[i].y));
      maps[i] = jacobianAt(Hinv, q);
    }
    const NccPatches warpedRef =
        NccPatches::warped(refGray_, refPoints_, maps, params_.correlation.halfWindow);
    const double half = params_.homography.guidedSearchHalfSizePx * s;
    matches = matcher_.match(refPoints_, warpedRef, points, patches, half, half, prediction);
    out.guided = true;
  } else {
    const double hw = params_.homography.reacquireWholeImage
                          ? gray.cols
                          : params_.correlation.searchHalfWidthPx * s;
    const double hh = params_.homography.reacquireWholeImage
                          ? gray.rows
                          : params_.correlation.searchHalfHeightPx * s;
    matches = matcher_.match(refPoints_, refPatches_, points, patches, hw, hh);
  }
  out.matches = static_cast<int>(matches.size());
  out.stageMs.emplace_back("matching", lap(clock));

  std::vector<cv::Point2f> src, dst;
  src.reserve(matches.size());
  dst.reserve(matches.size());
  for (const CornerMatch& m : matches) {
    src.push_back(refPoints_[static_cast<size_t>(m.first)]);
    dst.push_back(points[static_cast<size_t>(m.second)]);
  }
  const HomographyEstimate est = estimator_.estimate(src, dst, gray.size());
  out.stageMs.emplace_back("robust fit", lap(clock));
  out.frameCorners = points;
  for (size_t i = 0; i < src.size(); ++i)
    if (est.inliers[i]) out.inlierMatches.emplace_back(src[i], dst[i]);
  prevPoints_ = std::move(points);
  prevPatches_ = std::move(patches);
  out.inliers = est.inlierCount;
  if (!est.success) {
    out.failure = est.failure;
    lastH_.reset();
    return out;
  }
  // The paper's failure test: inliers among the reference corners this frame can see.
  const int margin = params_.correlation.halfWindow;
  int visible = 0;
  for (const cv::Point2f& r : refPoints_) {
    const cv::Point2d q = transferPoint(est.H, cv::Point2d(r.x, r.y));
    if (q.x >= margin && q.y >= margin && q.x < gray.cols - margin && q.y < gray.rows - margin)
      ++visible;
  }
  out.inlierRatio = static_cast<double>(est.inlierCount) / std::max(visible, est.inlierCount);
  out.H = est.H;
  if (out.inlierRatio < params_.ransac.minInlierRatio) {
    out.failure = "only " + std::to_string(est.inlierCount) + " of " + std::to_string(visible) +
                  " visible reference corners are inliers";
    lastH_.reset();
    return out;
  }
  out.tracked = true;
  lastH_ = est.H;
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
