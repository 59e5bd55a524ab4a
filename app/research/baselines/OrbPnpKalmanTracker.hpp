#pragma once
// OrbPnpKalmanTracker: the baseline users reach for today, after OpenCV's real-time pose
// estimation sample (samples/cpp/tutorial_code/calib3d/real_time_pose_estimation): ORB features
// of the frame matched (ratio test) to a model of ORB features of the two reference images,
// triangulated with their known poses,
// solvePnPRansac, and a constant-acceleration cv::KalmanFilter (18 states: position, velocity,
// acceleration, Euler angles and their rates) fed with the PnP pose when it has enough inliers.
// Used by the benchmark beside the PoseTracker, on the same frames.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/video/tracking.hpp>
#include <optional>

#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/ReferenceMap.hpp"

namespace reftrack::app {

struct OrbPnpKalmanParams {
  int features = 1000;         // ORB features per frame
  float ratioTest = 0.70f;     // the sample's ratio test
  int ransacIterations = 500;  // the sample's solvePnPRansac settings
  float reprojectionErrorPx = 6.0f;
  double confidence = 0.99;
  int minInliersKalman = 30;  // the sample updates the filter only above this
  double dt = 1.0 / 30.0;     // frame period
};

class OrbPnpKalmanTracker {
 public:
  explicit OrbPnpKalmanTracker(const ReferenceMap& map, OrbPnpKalmanParams params = {});
  // The filtered world->camera pose, or nullopt until the first good PnP measurement.
  std::optional<RigidPose> process(const cv::Mat& frame);
  // Forgets the filter's state: the next frame starts it again from its PnP pose (a cold start).
  void reset();
  int lastInliers() const { return lastInliers_; }
  int modelPoints() const { return static_cast<int>(modelPoints_.size()); }

 private:
  OrbPnpKalmanParams params_;
  cv::Ptr<cv::ORB> orb_;
  cv::BFMatcher matcher_{cv::NORM_HAMMING};
  std::vector<cv::Point3f> modelPoints_;  // world frame
  cv::Mat modelDescriptors_;
  cv::Matx33d K_;
  std::vector<double> dist_;
  cv::KalmanFilter kf_;
  bool initialised_ = false;
  int lastInliers_ = 0;
};

}  // namespace reftrack::app
