#include "app/viewer/VideoRecorder.hpp"

#include <cmath>
#include <opencv2/videoio.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace fs = std::filesystem;

fs::path VideoRecorder::trajectoryPathFor(const fs::path& mp4) {
  return mp4.parent_path() / (mp4.stem().string() + "_trajectory.txt");
}

VideoRecorder::VideoRecorder(const fs::path& mp4, double fps, cv::Size frameSize)
    : mp4_(mp4), trajectory_(trajectoryPathFor(mp4)), size_(frameSize) {
  const std::string where = "recording '" + mp4.string() + "'";
  if (mp4.extension() != ".mp4") throw Error(where + ": the file name must end in .mp4");
  const fs::path folder = mp4.has_parent_path() ? mp4.parent_path() : fs::path(".");
  if (!fs::is_directory(folder))
    throw Error(where + ": folder '" + folder.string() + "' does not exist");
  if (!(std::isfinite(fps) && fps > 0)) throw Error(where + ": frame rate must be positive");
  if (frameSize.width <= 0 || frameSize.height <= 0) throw Error(where + ": empty frame size");
  std::string partialName = mp4.stem().string();
  partialName.insert(partialName.begin(), '.');  // hidden; built so to dodge GCC 12 -Wrestrict
  partialName.append(".recording.mp4");
  partial_ = folder / partialName;
  tracked_.emplace(partial_);
  try {
    writer_.emplace(partial_, fps, frameSize);
  } catch (const Error& e) {
    std::error_code ec;
    fs::remove(partial_, ec);
    throw Error(where + ": " + e.what());
  }
  std::string trajectoryName = trajectory_.stem().string();
  trajectoryName.insert(trajectoryName.begin(), '.');
  trajectoryName.append(".recording.txt");
  partialTrajectory_ = folder / trajectoryName;
  trackedTrajectory_.emplace(partialTrajectory_);
  trajectoryOut_.open(partialTrajectory_);
  TumTrajectory::writeHeader(trajectoryOut_);
  if (!trajectoryOut_) {
    writer_.reset();
    std::error_code ec;
    fs::remove(partial_, ec);
    fs::remove(partialTrajectory_, ec);
    throw Error(where + ": the trajectory '" + partialTrajectory_.string() + "' cannot be written");
  }
}

VideoRecorder::~VideoRecorder() {
  if (closed_) return;
  writer_.reset();
  trajectoryOut_.close();
  std::error_code ec;
  fs::remove(partial_, ec);
  fs::remove(partialTrajectory_, ec);
}

void VideoRecorder::write(const cv::Mat& bgr, double timestamp,
                          const std::optional<RigidPose>& worldToCamera) {
  if (closed_) throw Error("recording '" + mp4_.string() + "' is already closed");
  if (bgr.size() != size_ || bgr.type() != CV_8UC3)
    throw Error("recording '" + mp4_.string() + "': frame " + std::to_string(frames_) + " is " +
                std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows) + " but the video is " +
                std::to_string(size_.width) + "x" + std::to_string(size_.height) + " BGR");
  // A write error (a full disk) stops the video but not the caller's run; close() reports it.
  if (videoError_.empty()) try {
      writer_->write(bgr);
    } catch (const Error& e) {
      videoError_ = e.what();
    }
  if (worldToCamera) {
    TumTrajectory::writeLine(trajectoryOut_, {timestamp, *worldToCamera});
    trajectoryOut_.flush();  // a crash keeps the lines of the frames already in the MP4
  }
  ++frames_;
}

void VideoRecorder::close() {
  if (closed_) return;
  closed_ = true;
  const auto discard = [&] {
    std::error_code ec;
    fs::remove(partial_, ec);
    fs::remove(partialTrajectory_, ec);
  };
  std::string videoError = videoError_;
  if (videoError.empty()) try {
      writer_->finish();
    } catch (const Error& e) {
      videoError = e.what();
    }
  writer_.reset();
  trajectoryOut_.close();
  if (!videoError.empty()) {
    discard();
    throw Error("recording '" + mp4_.string() + "' could not be finished: " + videoError);
  }
  if (frames_ == 0) {
    discard();
    throw Error("recording '" + mp4_.string() + "' holds no frame; nothing written");
  }
  if (!trajectoryOut_) {
    discard();
    throw Error("recording '" + mp4_.string() + "': the trajectory '" + trajectory_.string() +
                "' could not be written (is the disk full?)");
  }
  // Beside the writer's own error checks, the finished file must open and hold every frame
  // before it takes the final name. Reading the container's frame count costs no decoding.
  {
    cv::VideoCapture check(partial_.string(), cv::CAP_FFMPEG);
    const double stored = check.isOpened() ? check.get(cv::CAP_PROP_FRAME_COUNT) : -1.0;
    if (stored != static_cast<double>(frames_)) {
      discard();
      throw Error("recording '" + mp4_.string() + "' could not be finished (" +
                  (stored < 0 ? std::string("the MP4 is unreadable")
                              : std::to_string(static_cast<long long>(stored)) + " of " +
                                    std::to_string(frames_) + " frames stored") +
                  "): is the disk full or a file-size limit reached?");
    }
  }
  std::error_code ec;
  fs::rename(partialTrajectory_, trajectory_, ec);
  if (!ec) fs::rename(partial_, mp4_, ec);
  if (ec) {
    discard();
    fs::remove(trajectory_, ec);
    throw Error("recording '" + mp4_.string() + "' cannot be moved into place");
  }
  tracked_.reset();
  trackedTrajectory_.reset();
}

std::string closeRecording(VideoRecorder* recorder) {
  if (!recorder) return "";
  try {
    recorder->close();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace reftrack::app
