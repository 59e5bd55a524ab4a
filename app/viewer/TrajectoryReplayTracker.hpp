#pragma once
// TrajectoryReplayTracker: "tracks" by replaying a stored trajectory — the pose whose timestamp
// matches the frame's (within half a frame period), else the file's index-th pose (for files
// timestamped on another clock). Frames with neither report "lost". Used until the real trackers
// run, and to show ground truth.
#include <filesystem>

#include "app/viewer/FrameTracker.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack::app {

class TrajectoryReplayTracker final : public FrameTracker {
 public:
  // `fps`: the source frame rate (sets the timestamp tolerance). Throws reftrack::Error for an
  // empty trajectory or fps <= 0.
  TrajectoryReplayTracker(TumTrajectory trajectory, double fps);
  static TrajectoryReplayTracker load(const std::filesystem::path& file, double fps);

  TrackingResult process(const cv::Mat& frame, int index, double timestamp) override;
  void applyParams(const TrackerParams& params) override;
  std::string name() const override { return "trajectory replay"; }

 private:
  TumTrajectory trajectory_;
  double tolerance_;
};

}  // namespace reftrack::app
