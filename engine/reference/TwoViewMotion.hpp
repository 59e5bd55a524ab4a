#pragma once
// TwoViewMotion: how a calibrated camera moved between two views of an unprepared scene, from
// their own keypoints (no marker, no known pose): keypoints of each view (KeypointFeatures),
// ratio-test mutual matches, the essential matrix by five-point RANSAC on the undistorted pixels
// (cv::findEssentialMat) and the rotation and translation direction it holds (cv::recoverPose,
// the cheirality test). Says whether the pair can start a 3-D map, and if not why and what to do:
// a textureless view (too few keypoints), too little shared view (too few matches or inliers), a
// pure rotation (the rotation-only homography H = K R K^-1, R fitted to the inliers' viewing
// rays, explains most of the essential matrix's inliers: the translation is not seen) and too
// little parallax (the inliers' median angle between the two viewing rays, the first rotated by
// the essential matrix's R). The general homography is no test here: a scene's dominant plane
// (a desk, a wall) is explained by one under any motion. Thread-compatible (const methods).
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/UnpreparedMapParams.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

// One view's keypoints, described once (the first capture is compared with every later frame).
struct TwoViewKeyframe {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  std::vector<cv::Point2f> undistorted;  // the keypoints' pixels without the lens
};

struct TwoViewMotion {
  int keypointsFirst = 0, keypointsSecond = 0;
  int matches = 0;          // ratio-test mutual keypoint matches
  int inliers = 0;          // of the essential matrix
  int rotationInliers = 0;  // of those, explained by the best rotation alone within the threshold
  double rotationShare = 0.0;      // rotationInliers / inliers
  double medianParallaxDeg = 0.0;  // the inliers' median angle between the two viewing rays
  double medianParallaxPx = 0.0;   // ... as the pixel displacement a rotation does not explain
  // Second camera relative to the first: X_second = R X_first + t, |t| = 1 (direction only).
  RigidPose firstToSecond;
  // The second camera's centre in the first camera's frame (unit length): x right, y down,
  // z forward.
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();
  // The inlier matches (undistorted pixels in each view).
  std::vector<cv::Point2f> inlierFirst, inlierSecond;
  // A plane's homography fitted to the same matches (RANSAC, same threshold): its inliers, and
  // the motions its decomposition allows (cv::decomposeHomographyMat, those that keep its
  // inliers in front of both cameras; |t| = 1). A scene whose matches lie mostly on one plane
  // fixes the motion better through them than through the essential matrix: both are starts
  // for the refinement (UnpreparedInitializer).
  int homographyInliers = 0;
  std::vector<RigidPose> planeMotions;
  // Empty when the pair can start a map; else why not and what to do, in one sentence.
  std::string refusal;
  bool usable() const { return refusal.empty(); }
  // One line: matches, inliers, parallax, the rotation's share, the direction moved.
  std::string summary() const;
};

class TwoViewMotionEstimator {
 public:
  // Throws reftrack::Error on a bad camera or params (naming the field).
  TwoViewMotionEstimator(PinholeCamera camera, UnpreparedMapParams params = {});

  // Keypoints of an 8-bit BGR or grey image of the camera's size (else reftrack::Error).
  TwoViewKeyframe describe(const cv::Mat& image) const;
  // Empty, or why a view (named `which`, e.g. "first") is too textureless to start a map.
  std::string texturelessRefusal(const TwoViewKeyframe& view, const std::string& which) const;
  // The motion from `first` to `second`, with its refusal when the pair cannot start a map.
  TwoViewMotion estimate(const TwoViewKeyframe& first, const TwoViewKeyframe& second) const;
  TwoViewMotion estimate(const cv::Mat& first, const cv::Mat& second) const {
    return estimate(describe(first), describe(second));
  }

  const PinholeCamera& camera() const { return camera_; }
  const UnpreparedMapParams& params() const { return params_; }

 private:
  PinholeCamera camera_;
  UnpreparedMapParams params_;
};

}  // namespace reftrack
