#pragma once
// StatsHistory: the last N processed frames' figures for the Stats panel — loop rate, per-stage
// milliseconds, match and inlier counts, status, the pose components (tx ty tz rx ry rz of the
// world->camera pose, RigidPose::toVector6) and the overlay error, predicted from the pose
// covariance and, with ground truth, measured — oldest first.
#include <cstddef>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "app/viewer/FrameTracker.hpp"

namespace reftrack::app {

struct FrameStats {
  int index = 0;
  double loopMilliseconds = 0.0;  // wall time since the previous processed frame
  std::vector<StageTime> stages;
  int matches = 0, inliers = 0;
  std::string status;
  std::string advice;  // TrackingResult::advice
  std::optional<Vector6d> pose;
  // Overlay error of the drawn object (pixels): predicted from the pose covariance (6-DOF), and
  // the true one (mean distance of the object's points, estimated vs true pose) with ground truth.
  std::optional<double> predictedErrorPx, trueErrorPx;
};

class StatsHistory {
 public:
  explicit StatsHistory(std::size_t capacity = 300);
  void add(FrameStats stats);
  void clear() { frames_.clear(); }
  const std::deque<FrameStats>& frames() const { return frames_; }
  // Frames per second over the history (from loop times); 0 when unknown.
  double meanFps() const;
  // Pose component c (0..5) of every frame, NaN where the pose is unknown (gaps in plots).
  std::vector<float> poseSeries(int component) const;
  std::vector<float> inlierSeries() const;
  // The predicted / true overlay error of every frame, NaN where there is none.
  std::vector<float> predictedErrorSeries() const;
  std::vector<float> trueErrorSeries() const;
  // The viewer has ground truth for the frames: the Stats panel plots the true error too.
  void setGroundTruthLoaded(bool loaded) { groundTruthLoaded_ = loaded; }
  bool groundTruthLoaded() const { return groundTruthLoaded_; }

 private:
  std::size_t capacity_;
  std::deque<FrameStats> frames_;
  bool groundTruthLoaded_ = false;
};

}  // namespace reftrack::app
