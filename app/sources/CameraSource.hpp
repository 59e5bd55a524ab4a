#pragma once
// CameraSource: a live camera (V4L2 index N, as `camera:N`), timestamped by the steady clock
// from the first frame. Never ends by itself; a camera that cannot be opened or stops delivering
// frames throws reftrack::Error naming its index; reconnect() then reopens it when it returns.
#include <chrono>
#include <opencv2/videoio.hpp>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

class CameraSource final : public FrameSource {
 public:
  explicit CameraSource(int index);

  std::optional<Frame> next() override;
  std::optional<int> frameCount() const override { return std::nullopt; }
  double fps() const override { return fps_; }
  bool isLive() const override { return true; }
  bool reconnect() override;  // reopens /dev/videoN when it exists again
  std::string description() const override;

 private:
  int index_;
  cv::VideoCapture capture_;
  double fps_ = 30.0;
  int nextIndex_ = 0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace reftrack::app
