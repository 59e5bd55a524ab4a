#pragma once
// OrbPnpColdStart: the cold-start baseline the relocalisation experiment measures the Relocaliser
// against — OpenCV ORB features of the frame matched by brute force (Hamming, Lowe's ratio test)
// to the ORB keypoint layers of every reference of a MultiReferenceMap (the keypoints with a 3D
// point), then cv::solvePnPRansac on the 2D-3D matches; a pose only with minInliers inliers. No
// retrieval, no refinement, no verification: what a user would write with OpenCV alone.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <optional>
#include <string>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

struct OrbPnpColdStartParams {
  int features = 1000;               // ORB features per frame (640x480)
  float ratioTest = 0.8f;            // Lowe's ratio on the two nearest descriptors
  int ransacIterations = 300;        // solvePnPRansac
  float reprojectionErrorPx = 4.0f;  // inlier threshold (pixels of the frame)
  double confidence = 0.99;
  int minInliers = 20;
};

struct OrbPnpColdStartResult {
  std::optional<RigidPose> worldToCamera;  // world->camera, only with minInliers inliers
  int matches = 0, inliers = 0;
};

class OrbPnpColdStart {
 public:
  // Uses the map's keypoint layers; throws reftrack::Error unless they hold ORB descriptors
  // (CV_8U, 32 bytes) with at least minInliers 3D points in all.
  OrbPnpColdStart(const MultiReferenceMap& map, OrbPnpColdStartParams params = {});
  OrbPnpColdStartResult locate(const cv::Mat& frame) const;  // BGR or grey
  int modelPoints() const { return static_cast<int>(modelPoints_.size()); }

 private:
  OrbPnpColdStartParams params_;
  PinholeCamera camera_;
  cv::Ptr<cv::ORB> orb_;
  std::vector<cv::Point3f> modelPoints_;  // world frame
  cv::Mat modelDescriptors_;
};

}  // namespace reftrack::app
