#include "app/sources/VideoFileSource.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "engine/core/Error.hpp"

namespace reftrack::app {

VideoFileSource::VideoFileSource(const std::filesystem::path& file) : file_(file) {
  const std::string where = "video file '" + file.string() + "'";
  if (!std::filesystem::exists(file)) throw Error(where + " does not exist");
  if (std::filesystem::is_directory(file)) throw Error(where + " is a folder");
  try {
    capture_.open(file.string(), cv::CAP_FFMPEG);
  } catch (const cv::Exception& e) {
    throw Error(where + " cannot be opened: " + e.err);
  }
  if (!capture_.isOpened()) throw Error(where + " cannot be opened as a video");
  const double fps = capture_.get(cv::CAP_PROP_FPS);
  if (std::isfinite(fps) && fps > 0 && fps < 1000) fps_ = fps;
  const double count = capture_.get(cv::CAP_PROP_FRAME_COUNT);
  if (std::isfinite(count) && count > 0) count_ = static_cast<int>(count);
}

std::optional<Frame> VideoFileSource::next() {
  cv::Mat image;
  bool ok = false;
  try {
    ok = capture_.read(image);
  } catch (const cv::Exception& e) {
    throw Error("video file '" + file_.string() + "': frame " + std::to_string(nextIndex_) +
                " cannot be decoded: " + e.err);
  }
  if (!ok || image.empty()) {
    if (nextIndex_ == 0) throw Error("video file '" + file_.string() + "' holds no frame");
    return std::nullopt;
  }
  if (image.channels() == 1) cv::cvtColor(image, image, cv::COLOR_GRAY2BGR);
  Frame frame{image, nextIndex_, nextIndex_ / fps_};
  ++nextIndex_;
  return frame;
}

std::optional<int> VideoFileSource::frameCount() const {
  if (count_ > 0) return count_;
  return std::nullopt;
}

void VideoFileSource::seek(int index) {
  if (index < 0 || (count_ > 0 && index >= count_))
    throw Error(description() + ": frame " + std::to_string(index) + " is out of range");
  capture_.set(cv::CAP_PROP_POS_FRAMES, index);
  nextIndex_ = index;
}

std::string VideoFileSource::description() const {
  std::ostringstream s;
  s << "video '" << file_.string() << "' (";
  if (count_ > 0) s << count_ << " frames, ";
  s << fps_ << " fps)";
  return s.str();
}

}  // namespace reftrack::app
