#include "app/viewer/HomographyFrameTracker.hpp"

#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack::app {

HomographyFrameTracker::HomographyFrameTracker(const cv::Mat& reference,
                                               const TrackerParams& params,
                                               std::optional<PinholeCamera> camera,
                                               AnnotationSet labels)
    : reference_(toGray8(reference).clone()),
      camera_(std::move(camera)),
      labels_(std::move(labels)) {
  if (camera_ && camera_->imageSize() != reference_.size())
    throw Error("homography tracker: the camera is calibrated for " +
                std::to_string(camera_->imageSize().width) + "x" +
                std::to_string(camera_->imageSize().height) + " but the reference is " +
                std::to_string(reference_.cols) + "x" + std::to_string(reference_.rows));
  applyParams(params);
}

TrackingResult HomographyFrameTracker::process(const cv::Mat& frame, int, double) {
  last_ = tracker_->track(frame);
  TrackingResult r;
  r.status = last_.tracked ? "tracking" : "lost";
  if (!last_.tracked && !last_.failure.empty()) r.status += ": " + last_.failure;
  for (const auto& [stage, ms] : last_.stageMs) r.stages.push_back({stage, ms});
  r.matches = last_.matches;
  r.inliers = last_.inliers;
  r.debug.corners = last_.frameCorners;
  mappedLabels_.clear();
  if (last_.tracked) {
    r.debug.matches = last_.inlierMatches;  // reference position -> frame position
    r.H = last_.H.inv();
    mappedLabels_ = labels_.mapped(last_.H);
    if (camera_)
      r.worldToCamera =
          RigidPose(rotationFromHomography(last_.H, camera_->K()), Eigen::Vector3d::Zero());
  }
  return r;
}

void HomographyFrameTracker::applyParams(const TrackerParams& params) {
  tracker_ = std::make_unique<HomographyTracker>(
      reference_, params, camera_ ? std::optional<Eigen::Matrix3d>(camera_->K()) : std::nullopt);
}

}  // namespace reftrack::app
