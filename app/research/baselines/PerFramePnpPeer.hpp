#pragma once
// PerFramePnpPeer: the plain OpenCV answer to "where is the camera in this frame", given reference
// images with known poses and no tracking at all. Preparation: SIFT, AKAZE or ORB keypoints of
// every reference, each pair of references matched (brute force, Lowe's ratio test), the matches
// triangulated with the references' poses (cv::triangulatePoints on undistorted keypoints) and
// kept when they lie in front of both cameras and reproject within maxTriangulationErrorPx in
// both. Per frame: its keypoints matched the same way to each reference's keypoints, those with a
// 3D point giving 2D-3D pairs (undistorted), then cv::solvePnPRansac + cv::solvePnPRefineLM on
// the inliers; a pose only with minInliers inliers. The per-frame peer `bench-real` sets beside
// the tracker.
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "app/research/baselines/OpenCvFeatures.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"

namespace reftrack::app {

struct PerFramePnpPeerParams {
  // ORB only (SIFT and AKAZE keep OpenCV's defaults). Not the other ORB baselines' 1000: on the
  // desk clip's chessboard those 1000 crowd onto its repeating corners and the references share
  // 19 triangulated points (2000: 104).
  int orbFeatures = 2000;
  float ratioTest = 0.8f;                // Lowe (2004): nearest / second nearest distance
  double maxTriangulationErrorPx = 1.0;  // reprojection error in each of the two references
  int ransacIterations = 1000;           // solvePnPRansac
  double ransacErrorPxAt640x480 = 3.0;   // inlier threshold, scaled with the image's diagonal
  double ransacConfidence = 0.999;
  int minInliers = 15;
};

struct PerFramePnpResult {
  std::optional<RigidPose> worldToCamera;  // only with params.minInliers RANSAC inliers
  int keypoints = 0, matches = 0, inliers = 0;
};

// The peer's name in tables: "sift" -> "SIFT+PnP".
std::string perFramePnpPeerName(const std::string& detector);

class PerFramePnpPeer {
 public:
  // detector: "sift", "akaze" or "orb"; references: images (BGR or grey, the camera's size) with
  // their world->camera poses, at least two. Throws reftrack::Error on another detector name,
  // fewer than two references, a size other than the camera's, or fewer than 6 triangulated
  // points.
  PerFramePnpPeer(const std::string& detector, const PinholeCamera& camera,
                  const std::vector<cv::Mat>& referenceImages,
                  const std::vector<RigidPose>& referencePoses, PerFramePnpPeerParams params = {});

  PerFramePnpResult locate(const cv::Mat& frame) const;  // BGR or grey, the camera's size

  // Why `result` (of locate()) has no pose: "too few 2D-3D matches" or "too few PnP inliers".
  std::string noPoseReason(const PerFramePnpResult& result) const;

  const std::string& detectorName() const { return detectorName_; }
  const PerFramePnpPeerParams& params() const { return params_; }
  int modelPoints() const { return static_cast<int>(points_.size()); }  // triangulated points
  // Keypoints of reference r with a 3D point (a point may have one in each reference).
  int referencePoints(int r) const;

 private:
  struct Reference {
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    std::vector<int> point;  // per keypoint: index into points_, or -1
  };

  std::string detectorName_;
  PinholeCamera camera_;
  PerFramePnpPeerParams params_;
  OpenCvFeatures features_;
  std::vector<Reference> references_;
  std::vector<cv::Point3d> points_;  // world frame
  double ransacErrorPx_ = 3.0;
};

}  // namespace reftrack::app
