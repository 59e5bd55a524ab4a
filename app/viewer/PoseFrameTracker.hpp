#pragma once
// PoseFrameTracker: the 6-DOF MultiReferenceTracker behind the viewer's FrameTracker interface —
// the pose T_k, status (with the reason when not tracking), per-stage milliseconds, match/inlier
// counts, the pair of references in use and the relocalisation of the frame, and the debug layers
// (corners, inlier matches to V_A drawn from the reference position, epipolar lines of the V_A
// matches), and the overlay error the pose covariance predicts for the drawn object (status
// "uncertain: <why>" above pose.max_predicted_error_px). A two-reference map runs as a map of two.
#include <memory>

#include "app/viewer/FrameTracker.hpp"
#include "engine/tracking/MultiReferenceTracker.hpp"

namespace reftrack::app {

class PoseFrameTracker : public FrameTracker {
 public:
  PoseFrameTracker(MultiReferenceMap map, const TrackerParams& params);
  PoseFrameTracker(const ReferenceMap& map, const TrackerParams& params);
  TrackingResult process(const cv::Mat& frame, int index, double timestamp) override;
  void applyParams(const TrackerParams& params) override;
  std::string name() const override { return "6-DOF"; }
  std::vector<ReferenceImage> referenceImages() const override;
  void setOverlayPoints(const std::vector<Eigen::Vector3d>& worldPoints) override;
  // The map's dominant plane (placeOnDominantPlane; nullopt when it has none), found once.
  std::optional<ScenePlacement> scenePlacement() const override { return scene_; }
  void setRealTimeBudget(bool on) override;
  const MultiReferenceTracker& tracker() const { return tracker_; }
  MultiReferenceTracker& tracker() { return tracker_; }
  const MultiReferenceResult& last() const { return last_; }

 private:
  MultiReferenceTracker tracker_;
  MultiReferenceResult last_;
  std::optional<ScenePlacement> scene_;
};

}  // namespace reftrack::app
