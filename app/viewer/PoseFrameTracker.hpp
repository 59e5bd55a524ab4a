#pragma once
// PoseFrameTracker: the 6-DOF PoseTracker behind the viewer's FrameTracker interface — the pose
// T_k, status, per-stage milliseconds, match/inlier counts and the debug layers (corners, inlier
// matches to V_A drawn from the reference position, epipolar lines of the V_A matches).
#include <memory>

#include "app/viewer/FrameTracker.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack::app {

class PoseFrameTracker : public FrameTracker {
 public:
  PoseFrameTracker(ReferenceMap map, const TrackerParams& params);
  TrackingResult process(const cv::Mat& frame, int index, double timestamp) override;
  void applyParams(const TrackerParams& params) override;
  std::string name() const override { return "6-DOF"; }
  const PoseTracker& tracker() const { return tracker_; }
  PoseTracker& tracker() { return tracker_; }
  const PoseTrackingResult& last() const { return last_; }

 private:
  PoseTracker tracker_;
  PoseTrackingResult last_;
};

}  // namespace reftrack::app
