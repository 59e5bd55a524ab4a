#include "app/viewer/TrajectoryReplayTracker.hpp"

#include <chrono>
#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack::app {

TrajectoryReplayTracker::TrajectoryReplayTracker(TumTrajectory trajectory, double fps)
    : trajectory_(std::move(trajectory)) {
  if (trajectory_.poses.empty()) throw Error("replayed trajectory holds no pose");
  if (!(std::isfinite(fps) && fps > 0)) throw Error("replayed trajectory: fps must be positive");
  tolerance_ = 0.5 / fps;
}

TrajectoryReplayTracker TrajectoryReplayTracker::load(const std::filesystem::path& file,
                                                      double fps) {
  TumTrajectory trajectory = TumTrajectory::load(file);
  if (trajectory.poses.empty()) throw Error("trajectory file '" + file.string() + "' is empty");
  return TrajectoryReplayTracker(std::move(trajectory), fps);
}

TrackingResult TrajectoryReplayTracker::process(const cv::Mat&, int index, double timestamp) {
  const auto start = std::chrono::steady_clock::now();
  TrackingResult result;
  result.worldToCamera = trajectory_.poseAt(timestamp, tolerance_);
  if (!result.worldToCamera && index >= 0 && index < static_cast<int>(trajectory_.poses.size()))
    result.worldToCamera = trajectory_.poses[index].worldToCamera;
  result.status = result.worldToCamera ? "tracking" : "lost";
  result.stages.push_back(
      {"replay", std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                     .count()});
  return result;
}

void TrajectoryReplayTracker::applyParams(const TrackerParams& params) { params.check(); }

}  // namespace reftrack::app
