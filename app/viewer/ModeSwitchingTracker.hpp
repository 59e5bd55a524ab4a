#pragma once
// ModeSwitchingTracker: the viewer's live tracker when both kinds may run — the 6-DOF tracker
// (given a reference map) and the homography tracker (given a reference frame). The Tracking
// panel's mode switch reaches it through applyParams(): the tracker of the selected mode takes
// over from the next frame; selecting a mode whose input was not given is an error that names
// the missing option.
#include <memory>

#include "app/viewer/FrameTracker.hpp"

namespace reftrack::app {

class ModeSwitchingTracker : public FrameTracker {
 public:
  // Either may be null, not both.
  ModeSwitchingTracker(std::unique_ptr<FrameTracker> sixDof,
                       std::unique_ptr<FrameTracker> homography, TrackingMode initial);
  TrackingResult process(const cv::Mat& frame, int index, double timestamp) override;
  void applyParams(const TrackerParams& params) override;
  std::string name() const override { return active().name(); }
  // The 6-DOF tracker's reference images (whichever mode is active).
  std::vector<ReferenceImage> referenceImages() const override {
    return sixDof_ ? sixDof_->referenceImages() : std::vector<ReferenceImage>{};
  }
  // Given to the 6-DOF tracker (whichever mode is active).
  void setOverlayPoints(const std::vector<Eigen::Vector3d>& worldPoints) override {
    if (sixDof_) sixDof_->setOverlayPoints(worldPoints);
  }
  // The 6-DOF tracker's scene (whichever mode is active).
  std::optional<ScenePlacement> scenePlacement() const override {
    return sixDof_ ? sixDof_->scenePlacement() : std::nullopt;
  }
  // Given to the 6-DOF tracker (whichever mode is active).
  void setRealTimeBudget(bool on) override {
    if (sixDof_) sixDof_->setRealTimeBudget(on);
  }

 private:
  FrameTracker& active() const;
  std::unique_ptr<FrameTracker> sixDof_, homography_;
  TrackingMode mode_;
};

}  // namespace reftrack::app
