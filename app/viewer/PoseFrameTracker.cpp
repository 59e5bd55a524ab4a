#include "app/viewer/PoseFrameTracker.hpp"

#include "engine/core/Error.hpp"
#include "engine/core/ThreadCpuClock.hpp"
#include "engine/geometry/FundamentalMatrix.hpp"

namespace reftrack::app {

namespace {

std::optional<ScenePlacement> findScene(const MultiReferenceMap& map) {
  try {
    return placeOnDominantPlane(map);
  } catch (const Error&) {
    return std::nullopt;  // too few points or no plane: the object stays where the settings say
  }
}

}  // namespace

PoseFrameTracker::PoseFrameTracker(MultiReferenceMap map, const TrackerParams& params)
    : tracker_(std::move(map), params), scene_(findScene(tracker_.map())) {}

PoseFrameTracker::PoseFrameTracker(const ReferenceMap& map, const TrackerParams& params)
    : tracker_(MultiReferenceMap::fromPair(map), params), scene_(findScene(tracker_.map())) {}

TrackingResult PoseFrameTracker::process(const cv::Mat& frame, int, double) {
  last_ = tracker_.process(frame);
  const PoseTrackingResult& p = last_.tracking;
  TrackingResult r;
  r.worldToCamera = p.worldToCamera;
  r.status = toString(p.state);
  if (p.state != TrackingState::Tracking) r.status += ": " + p.message;
  r.predictedErrorPx = last_.predictedErrorPx;
  r.uncertain = last_.uncertain;
  if (last_.uncertain) r.status = "uncertain: " + last_.uncertainReason;
  for (const StageTiming& t : p.timings) r.stages.push_back({t.stage, t.ms});
  r.matches = p.matchesA + p.matchesB;
  r.inliers = p.inliers;
  r.rollingShutterReadout = p.rollingShutterReadout;
  r.debug.corners = p.frameCorners;
  ReferencesFrame refs;
  refs.referenceA = last_.referenceA;
  refs.referenceB = last_.referenceB;
  refs.relocalisationAttempted = last_.relocalisation.attempted;
  refs.relocalisationSucceeded = last_.relocalisation.succeeded;
  refs.relocalisationMs = last_.relocalisation.ms;
  refs.relocalisationMessage = last_.relocalisation.message;
  r.references = refs;
  // Match segments from where the corner sits in V_A to where it is now.
  for (const auto& m : p.inliersA) r.debug.matches.emplace_back(m.second, m.first);
  if (p.T_Ak) {
    // Epipolar lines in the frame of a few V_A matches: l = F_Ak p_A (undistorted geometry;
    // drawn on the distorted frame, which is exact only without lens distortion).
    const Eigen::Matrix3d F = fundamentalMatrix(tracker_.map().camera.K(), *p.T_Ak);
    const std::size_t step = std::max<std::size_t>(1, p.inliersA.size() / 12);
    for (std::size_t i = 0; i < p.inliersA.size(); i += step) {
      const cv::Point2f& pA = p.inliersA[i].second;
      const Eigen::Vector3d l = F * Eigen::Vector3d(pA.x, pA.y, 1.0);
      if (l.head<2>().norm() > 0) r.debug.epipolarLines.emplace_back(l.x(), l.y(), l.z());
    }
  }
  return r;
}

void PoseFrameTracker::applyParams(const TrackerParams& params) { tracker_.setParams(params); }

void PoseFrameTracker::setRealTimeBudget(bool on) {
  tracker_.setBudgetClock(on ? std::function<double()>(processCpuMs) : std::function<double()>());
}

void PoseFrameTracker::setOverlayPoints(const std::vector<Eigen::Vector3d>& worldPoints) {
  if (worldPoints != tracker_.overlayPoints()) tracker_.setOverlayPoints(worldPoints);
}

std::vector<ReferenceImage> PoseFrameTracker::referenceImages() const {
  std::vector<ReferenceImage> images;
  for (const ReferenceView& v : tracker_.map().views) images.push_back({v.name, v.image});
  return images;
}

}  // namespace reftrack::app
