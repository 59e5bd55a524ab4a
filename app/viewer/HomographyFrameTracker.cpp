#include "app/viewer/HomographyFrameTracker.hpp"

#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"
#include "engine/geometry/PixelDistortion.hpp"
#include "engine/homography/LensTransfer.hpp"

namespace reftrack::app {

HomographyFrameTracker::HomographyFrameTracker(const cv::Mat& reference,
                                               const TrackerParams& params,
                                               std::optional<PinholeCamera> camera,
                                               AnnotationSet labels)
    : reference_(toGray8(reference).clone()),
      camera_(std::move(camera)),
      labels_(std::move(labels)) {
  sameCamera_ = camera_ && camera_->imageSize() == reference_.size();
  if (camera_ && camera_->hasDistortion()) {
    undistorter_.emplace(*camera_);
    if (sameCamera_) reference_ = undistorter_->undistort(reference_);
  }
  applyParams(params);
}

TrackingResult HomographyFrameTracker::process(const cv::Mat& frame, int, double) {
  if (camera_ && frame.size() != camera_->imageSize())
    throw Error("homography tracker: the frame is " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + " but the camera is calibrated for " +
                std::to_string(camera_->imageSize().width) + "x" +
                std::to_string(camera_->imageSize().height));
  last_ = tracker_->track(undistorter_ ? undistorter_->undistort(toGray8(frame)) : frame);
  TrackingResult r;
  r.status = last_.tracked ? "tracking" : "lost";
  if (!last_.tracked && !last_.failure.empty()) r.status += ": " + last_.failure;
  advice_.add(last_, tracker_->referenceSize(), frame.size());
  r.advice = advice_.advice().value_or("");
  for (const auto& [stage, ms] : last_.stageMs) r.stages.push_back({stage, ms});
  r.matches = last_.matches;
  r.inliers = last_.inliers;
  r.debug.corners = toRecorded(last_.frameCorners);
  mappedLabels_.clear();
  if (last_.tracked) {
    // reference position -> frame position
    if (undistorter_) {
      std::vector<cv::Point2f> from, to;
      for (const auto& [a, b] : last_.inlierMatches) {
        from.push_back(a);
        to.push_back(b);
      }
      if (sameCamera_) from = toRecorded(from);  // else the reference's pixels as recorded
      to = toRecorded(to);
      for (std::size_t i = 0; i < from.size(); ++i) r.debug.matches.emplace_back(from[i], to[i]);
    } else {
      r.debug.matches = last_.inlierMatches;
    }
    r.H = last_.H.inv();
    if (undistorter_) {
      std::vector<cv::Point2d> positions;
      for (const Annotation& a : labels_.labels()) positions.push_back(a.position);
      mappedLabels_ = transferThroughLens(last_.H, positions, *camera_, sameCamera_);
    } else {
      mappedLabels_ = labels_.mapped(last_.H);
    }
    if (camera_ && sameCamera_ && frame.size() == reference_.size())
      r.worldToCamera =
          RigidPose(rotationFromHomography(last_.H, camera_->K()), Eigen::Vector3d::Zero());
  }
  return r;
}

std::vector<cv::Point2f> HomographyFrameTracker::toRecorded(
    const std::vector<cv::Point2f>& undistorted) const {
  return undistorter_ ? distortPixels(*camera_, undistorted) : undistorted;
}

void HomographyFrameTracker::applyParams(const TrackerParams& params) {
  tracker_ = std::make_unique<HomographyTracker>(
      reference_, params, camera_ ? std::optional<Eigen::Matrix3d>(camera_->K()) : std::nullopt);
}

}  // namespace reftrack::app
