#include "app/viewer/ModeSwitchingTracker.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
void requireAvailable(const std::unique_ptr<FrameTracker>& tracker, TrackingMode mode) {
  if (tracker) return;
  throw Error(mode == TrackingMode::SixDof
                  ? "6dof mode needs a reference map (--map scene/ from `reftrack prepare`)"
                  : "homography mode needs a reference frame (--reference ref.png)");
}
}  // namespace

ModeSwitchingTracker::ModeSwitchingTracker(std::unique_ptr<FrameTracker> sixDof,
                                           std::unique_ptr<FrameTracker> homography,
                                           TrackingMode initial)
    : sixDof_(std::move(sixDof)), homography_(std::move(homography)), mode_(initial) {
  if (!sixDof_ && !homography_) throw Error("no tracker: give --map and/or --reference");
  if (!(mode_ == TrackingMode::SixDof ? sixDof_ : homography_))
    mode_ = sixDof_ ? TrackingMode::SixDof : TrackingMode::Homography;
}

FrameTracker& ModeSwitchingTracker::active() const {
  return mode_ == TrackingMode::SixDof ? *sixDof_ : *homography_;
}

TrackingResult ModeSwitchingTracker::process(const cv::Mat& frame, int index, double timestamp) {
  return active().process(frame, index, timestamp);
}

void ModeSwitchingTracker::applyParams(const TrackerParams& params) {
  requireAvailable(params.mode == TrackingMode::SixDof ? sixDof_ : homography_, params.mode);
  FrameTracker& next = params.mode == TrackingMode::SixDof ? *sixDof_ : *homography_;
  next.applyParams(params);
  mode_ = params.mode;
}

}  // namespace reftrack::app
