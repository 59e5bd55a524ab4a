#pragma once
// StatsHistory: the last N processed frames' figures for the Stats panel — loop rate, per-stage
// milliseconds, match and inlier counts, status and the pose components (tx ty tz rx ry rz of
// the world->camera pose, RigidPose::toVector6) — oldest first.
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
  std::optional<Vector6d> pose;
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

 private:
  std::size_t capacity_;
  std::deque<FrameStats> frames_;
};

}  // namespace reftrack::app
