#pragma once
// OrbPnpRelocaliser: the relocalisation baseline users reach for today — plain OpenCV: ORB on the
// frame, brute-force Hamming kNN with a ratio test against every reference's ORB keypoints that
// have a 3D point (one pooled set, no retrieval), solvePnPRansac with OpenCV's default settings,
// a pose when it has `minInliers` inliers. Used by the relocalisation benchmark beside the
// Relocaliser, against the same map's keypoint layer (which must be ORB).
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <optional>

#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/MultiReferenceMap.hpp"

namespace reftrack::app {

struct OrbPnpRelocaliserParams {
  int features = 1000;     // ORB features per 640x480 frame (scaled with the area)
  float ratioTest = 0.8f;  // Lowe's ratio
  int minInliers = 20;     // the same acceptance count as the Relocaliser's default
};

class OrbPnpRelocaliser {
 public:
  // Throws reftrack::Error when the map's keypoint layer is not ORB or has no 3D points.
  explicit OrbPnpRelocaliser(const MultiReferenceMap& map, OrbPnpRelocaliserParams params = {});
  // World->camera pose, or nullopt (too few matches or inliers). Grey or BGR.
  std::optional<RigidPose> locate(const cv::Mat& frame) const;
  int modelPoints() const { return static_cast<int>(points_.size()); }

 private:
  OrbPnpRelocaliserParams params_;
  cv::Ptr<cv::ORB> orb_;
  std::vector<cv::Point3f> points_;
  cv::Mat descriptors_;
  cv::Matx33d K_;
  std::vector<double> dist_;
};

}  // namespace reftrack::app
