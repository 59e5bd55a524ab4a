#include "app/viewer/PoseFrameTracker.hpp"

#include "engine/geometry/FundamentalMatrix.hpp"

namespace reftrack::app {

PoseFrameTracker::PoseFrameTracker(ReferenceMap map, const TrackerParams& params)
    : tracker_(std::move(map), params) {}

TrackingResult PoseFrameTracker::process(const cv::Mat& frame, int, double) {
  last_ = tracker_.process(frame);
  TrackingResult r;
  r.worldToCamera = last_.worldToCamera;
  r.status = toString(last_.state);
  if (last_.state == TrackingState::Lost) r.status += ": " + last_.message;
  for (const StageTiming& t : last_.timings) r.stages.push_back({t.stage, t.ms});
  r.matches = last_.matchesA + last_.matchesB;
  r.inliers = last_.inliers;
  r.debug.corners = last_.frameCorners;
  // Match segments from where the corner sits in V_A to where it is now.
  for (const auto& m : last_.inliersA) r.debug.matches.emplace_back(m.second, m.first);
  if (last_.T_Ak) {
    // Epipolar lines in the frame of a few V_A matches: l = F_Ak p_A (undistorted geometry;
    // drawn on the distorted frame, which is exact only without lens distortion).
    const Eigen::Matrix3d F = fundamentalMatrix(tracker_.map().camera.K(), *last_.T_Ak);
    const std::size_t step = std::max<std::size_t>(1, last_.inliersA.size() / 12);
    for (std::size_t i = 0; i < last_.inliersA.size(); i += step) {
      const cv::Point2f& pA = last_.inliersA[i].second;
      const Eigen::Vector3d l = F * Eigen::Vector3d(pA.x, pA.y, 1.0);
      if (l.head<2>().norm() > 0) r.debug.epipolarLines.emplace_back(l.x(), l.y(), l.z());
    }
  }
  return r;
}

void PoseFrameTracker::applyParams(const TrackerParams& params) { tracker_.setParams(params); }

}  // namespace reftrack::app
