#pragma once
// FrameTracker: what the viewer loop (window, headless, demo, `track --record`) calls once per
// frame. Implementations: TrajectoryReplayTracker (poses from a TUM file); the homography and
// 6-DOF trackers plug in behind the same interface.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "engine/config/TrackerParams.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/mapping/ScenePlacement.hpp"

namespace reftrack::app {

struct StageTime {
  std::string name;
  double milliseconds = 0.0;
};

// 2-D debug primitives in frame pixels (pixel centres at integers).
struct TrackingDebug {
  std::vector<cv::Point2f> corners;
  std::vector<std::pair<cv::Point2f, cv::Point2f>> matches;  // from (reference side) -> to
  std::vector<cv::Vec3d> epipolarLines;                      // a x + b y + c = 0
};

// 6-DOF tracking over a multi-reference map: the pair in use (-1: none) and this frame's
// relocalisation, if one was attempted.
struct ReferencesFrame {
  int referenceA = -1, referenceB = -1;
  bool relocalisationAttempted = false, relocalisationSucceeded = false;
  double relocalisationMs = 0.0;
  std::string relocalisationMessage;
};

// A reference image of the tracker's map, for the References panel.
struct ReferenceImage {
  std::string name;
  cv::Mat image;  // BGR or grey, as stored in the map
};

struct TrackingResult {
  std::optional<RigidPose> worldToCamera;  // set when a 6-DOF pose is known for the frame
  std::optional<cv::Matx33d> H;            // frame -> reference homography, homography mode
  std::string status = "initialising";     // "tracking", "uncertain", "lost" or "initialising"
  std::vector<StageTime> stages;           // per-stage milliseconds, in order
  int matches = 0;
  int inliers = 0;
  TrackingDebug debug;
  std::optional<ReferencesFrame> references;    // set by the multi-reference 6-DOF tracker
  std::optional<double> rollingShutterReadout;  // 6-DOF: the readout in use (fixed or estimated)
  // 6-DOF: the overlay error the pose covariance predicts for the overlay object (pixels), and
  // whether it exceeds pose.max_predicted_error_px (status "uncertain: ..."; the object is then
  // not drawn as if exact: OverlayCompositor).
  std::optional<double> predictedErrorPx;
  bool uncertain = false;
  // Advice for the user while the recent frames show a known failure pattern (homography mode on
  // a view that is not one plane: NonPlanarAdvice); empty else.
  std::string advice;
};

class FrameTracker {
 public:
  virtual ~FrameTracker() = default;
  virtual TrackingResult process(const cv::Mat& frame, int index, double timestamp) = 0;
  // Takes effect from the next process() call; throws reftrack::Error for invalid parameters.
  virtual void applyParams(const TrackerParams& params) = 0;
  virtual std::string name() const = 0;
  // The reference images of the map it tracks against (empty: no References panel).
  virtual std::vector<ReferenceImage> referenceImages() const { return {}; }
  // The drawn object's points in the world frame, for the predicted overlay error (6-DOF); the
  // other trackers predict none and ignore them.
  virtual void setOverlayPoints(const std::vector<Eigen::Vector3d>& /*worldPoints*/) {}
  // Where the overlay object stands by default in the tracked scene (6-DOF: on its map's
  // dominant plane, OverlaySettings::applyScene); nullopt: no scene known.
  virtual std::optional<ScenePlacement> scenePlacement() const { return std::nullopt; }
  // 6-DOF: the search after a loss budgeted in measured CPU time (a live camera) instead of the
  // modelled cost of its work (MultiReferenceTracker::setBudgetClock); the others ignore it.
  virtual void setRealTimeBudget(bool /*on*/) {}
};

}  // namespace reftrack::app
