#pragma once
// HomographyFrameTracker: the HomographyTracker (homography mode, paper Sec. 7.3) behind the
// viewer's FrameTracker interface — status, per-stage milliseconds, match/inlier counts, the
// debug layers (frame corners, inlier matches drawn from the reference position), TrackingResult
// H (frame -> reference, as FrameTracker documents) and, given the camera, the rotation-only pose
// R = K^-1 H K (world = the reference camera's frame, zero translation). Labels of the reference
// frame are mapped into each registered frame (mappedLabels()).
// The camera is the frames' camera. The reference may have any size: of the camera's size it is
// taken to come from the same camera (undistorted with it; the rotation-only model and pose
// apply), of another size from another camera whose intrinsics are unknown (used as recorded;
// general homography only, no pose). A camera with lens distortion has every frame (and a
// same-camera reference) undistorted (FrameUndistorter) before registration: the homography
// (last().H, TrackingResult H, the pose) then relates undistorted pixels, while the debug layers
// and mappedLabels() are distorted back onto the recorded frame.
#include <memory>
#include <optional>

#include "app/tracking/NonPlanarAdvice.hpp"
#include "app/viewer/FrameTracker.hpp"
#include "engine/geometry/FrameUndistorter.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/AnnotationSet.hpp"
#include "engine/homography/HomographyTracker.hpp"

namespace reftrack::app {

class HomographyFrameTracker : public FrameTracker {
 public:
  // Throws reftrack::Error as HomographyTracker does.
  HomographyFrameTracker(const cv::Mat& reference, const TrackerParams& params,
                         std::optional<PinholeCamera> camera = {}, AnnotationSet labels = {});

  TrackingResult process(const cv::Mat& frame, int index, double timestamp) override;
  // Rebuilds the tracker on the same reference with the new RANSAC/correlation/corner settings;
  // the next frame is matched unguided. Throws (keeping the old tracker) on invalid params.
  void applyParams(const TrackerParams& params) override;
  std::string name() const override { return "homography"; }

  const HomographyTrackResult& last() const { return last_; }
  const AnnotationSet& labels() const { return labels_; }
  // Label positions in the last processed frame (empty when it was not registered).
  const std::vector<cv::Point2d>& mappedLabels() const { return mappedLabels_; }
  const HomographyTracker& tracker() const { return *tracker_; }
  const NonPlanarAdvice& advice() const { return advice_; }
  // The reference's size, and whether it comes from the frames' camera (it has its size).
  cv::Size referenceSize() const { return reference_.size(); }
  bool referenceSharesCamera() const { return sameCamera_; }

 private:
  // Undistorted pixels -> the recorded frame's (unchanged without distortion).
  std::vector<cv::Point2f> toRecorded(const std::vector<cv::Point2f>& undistorted) const;

  cv::Mat reference_;  // grey; undistorted when the camera has distortion
  std::optional<FrameUndistorter> undistorter_;
  std::unique_ptr<HomographyTracker> tracker_;
  std::optional<PinholeCamera> camera_;
  bool sameCamera_ = false;  // the reference comes from camera_ (has its size)
  AnnotationSet labels_;
  HomographyTrackResult last_;
  NonPlanarAdvice advice_;
  std::vector<cv::Point2d> mappedLabels_;
};

}  // namespace reftrack::app
