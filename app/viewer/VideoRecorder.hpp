#pragma once
// VideoRecorder: writes composited frames to a fragmented MP4 (FragmentedMp4Writer) at the source
// frame rate, one output frame per call, and the trajectory used beside it as TUM
// (`<stem>_trajectory.txt`, tracked frames only, streamed to disk line by line so memory stays
// flat over long recordings). Both are written under temporary names and
// renamed by close(), so an error or an abandoned recording (destroyed without close()) leaves
// no half-written file at the target paths.
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "app/viewer/FragmentedMp4Writer.hpp"
#include "engine/core/TemporaryOutputs.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack::app {

class VideoRecorder {
 public:
  // Throws reftrack::Error naming the path when it does not end in .mp4, its folder does not
  // exist, fps <= 0 or the writer cannot be opened.
  VideoRecorder(const std::filesystem::path& mp4, double fps, cv::Size frameSize);
  ~VideoRecorder();
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;

  // Appends one BGR frame of the size given at construction (throws reftrack::Error otherwise)
  // and, when known, the world->camera pose used for it.
  void write(const cv::Mat& bgr, double timestamp, const std::optional<RigidPose>& worldToCamera);
  // Finishes the MP4 and the trajectory and moves both to their final names.
  void close();

  int framesWritten() const { return frames_; }
  cv::Size frameSize() const { return size_; }  // the size write() takes
  const std::filesystem::path& videoPath() const { return mp4_; }
  const std::filesystem::path& trajectoryPath() const { return trajectory_; }
  // `<folder>/<stem>_trajectory.txt` for `<folder>/<stem>.mp4`.
  static std::filesystem::path trajectoryPathFor(const std::filesystem::path& mp4);

 private:
  std::filesystem::path mp4_, trajectory_, partial_;
  std::optional<TemporaryOutput> tracked_;  // partial_, removed if a signal ends the process
  std::filesystem::path partialTrajectory_;
  std::ofstream trajectoryOut_;
  std::optional<TemporaryOutput> trackedTrajectory_;
  cv::Size size_;
  std::optional<FragmentedMp4Writer> writer_;
  std::string videoError_;  // the first write error; the video stops there
  int frames_ = 0;
  bool closed_ = false;
};

// Closes `recorder` (none: nothing to do) and returns the error message of a recording that
// cannot be finished (a full disk) instead of throwing it, so the caller's other outputs are
// still written before it reports the failure; "" on success.
std::string closeRecording(VideoRecorder* recorder);

}  // namespace reftrack::app
