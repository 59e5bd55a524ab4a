#include "app/sources/CameraSource.hpp"

#include <cmath>
#include <filesystem>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

CameraSource::CameraSource(int index) : index_(index) {
  const std::string where = "camera " + std::to_string(index);
  if (index < 0) throw Error(where + ": the camera index must be 0 or more");
  const std::string device = "/dev/video" + std::to_string(index);
  // Checked first: OpenCV's V4L2 backend only warns on stderr for a missing device.
  if (!std::filesystem::exists(device)) throw Error(where + " does not exist (no " + device + ")");
  try {
    capture_.open(index, cv::CAP_V4L2);
  } catch (const cv::Exception& e) {
    throw Error(where + " cannot be opened: " + e.err);
  }
  if (!capture_.isOpened()) throw Error(where + " (" + device + ") cannot be opened");
  const double fps = capture_.get(cv::CAP_PROP_FPS);
  if (std::isfinite(fps) && fps > 0 && fps < 1000) fps_ = fps;
}

std::optional<Frame> CameraSource::next() {
  cv::Mat image;
  if (!capture_.read(image) || image.empty())
    throw Error("camera " + std::to_string(index_) + " stopped delivering frames");
  const auto now = std::chrono::steady_clock::now();
  if (nextIndex_ == 0) start_ = now;
  if (image.channels() == 1) cv::cvtColor(image, image, cv::COLOR_GRAY2BGR);
  Frame frame{image, nextIndex_, std::chrono::duration<double>(now - start_).count()};
  ++nextIndex_;
  return frame;
}

bool CameraSource::reconnect() {
  capture_.release();
  if (!std::filesystem::exists("/dev/video" + std::to_string(index_))) return false;
  try {
    return capture_.open(index_, cv::CAP_V4L2) && capture_.isOpened();
  } catch (const cv::Exception&) {
    return false;
  }
}

std::string CameraSource::description() const {
  return "camera " + std::to_string(index_) + " (live)";
}

}  // namespace reftrack::app
