#pragma once
// HomographyTracker (paper Sec. 7.3, SPEC §5): registers each frame to a stored reference frame
// with one homography H (reference -> frame). While tracking, the frame is predicted from the
// previous result: the frame-to-frame homography (previous -> current, narrow-baseline matches
// + RANSAC) chained with the last reference -> previous one; reference corners are matched
// around their predicted positions with reference windows warped by the prediction (Eq. 19
// style), solved robustly and refined. A frame with too few inliers among the reference corners
// that fall inside it is flagged lost; while lost every frame is matched unguided (square
// windows, whole image), so tracking re-acquires on its own when the view returns.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/features/Corner.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/homography/RobustHomographyEstimator.hpp"
#include "engine/matching/NarrowBaselineMatcher.hpp"
#include "engine/matching/NccCorrelation.hpp"

namespace reftrack {

struct HomographyTrackResult {
  bool tracked = false;
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> this frame (meaningful when tracked)
  double inlierRatio = 0.0;            // inliers / reference corners mapped inside this frame
  int corners = 0;                     // corners detected in this frame
  int matches = 0;                     // correlation matches to the reference
  int inliers = 0;
  bool guided = false;  // matched around a prediction (false: unguided re-acquisition)
  std::string failure;  // why the frame was not tracked
  std::vector<cv::Point2f> frameCorners;  // corner positions detected in this frame
  // Inlier correspondences (reference position, frame position) of the final H.
  std::vector<std::pair<cv::Point2f, cv::Point2f>> inlierMatches;
  // Milliseconds per stage, in order: corners, prediction, matching, robust fit.
  std::vector<std::pair<std::string, double>> stageMs;
};

class HomographyTracker {
 public:
  // reference: the stored frame (8-bit grey or BGR). Throws reftrack::Error on an empty image,
  // bad parameters, or a reference with fewer than 8 corners.
  HomographyTracker(const cv::Mat& reference, const TrackerParams& params);

  // Frames must have the reference's size (else reftrack::Error naming both sizes).
  HomographyTrackResult track(const cv::Mat& frame);
  void reset();  // forget the previous frame: the next one is matched unguided

  const std::vector<Corner>& referenceCorners() const { return refCorners_; }
  cv::Size imageSize() const { return refGray_.size(); }
  bool lost() const { return !lastH_.has_value(); }

 private:
  std::optional<cv::Matx33d> predict(const std::vector<cv::Point2f>& points,
                                     const NccPatches& patches) const;

  TrackerParams params_;
  CornerDetector detector_;
  NarrowBaselineMatcher matcher_;
  RobustHomographyEstimator estimator_;
  cv::Mat refGray_;
  std::vector<Corner> refCorners_;
  std::vector<cv::Point2f> refPoints_;
  NccPatches refPatches_;
  // The previous frame (for the frame-to-frame homography) and its registration.
  std::optional<cv::Matx33d> lastH_;
  std::vector<cv::Point2f> prevPoints_;
  NccPatches prevPatches_;
};

// Rotation-only pose for a camera that only rotates: H = K R K^-1 gives R = K^-1 H K, scaled to
// unit determinant and projected onto SO(3). R maps reference-camera coordinates to the
// current camera's (X_cur = R X_ref).
Eigen::Matrix3d rotationFromHomography(const cv::Matx33d& H, const Eigen::Matrix3d& K);

}  // namespace reftrack
