#pragma once
// VideoFileSource: the frames of a video file (any container and codec OpenCV's FFmpeg backend
// reads), timestamped index / fps. Throws reftrack::Error naming the file when it is missing or
// cannot be decoded.
#include <filesystem>
#include <memory>
#include <opencv2/videoio.hpp>

#include "app/sources/FrameSource.hpp"

namespace reftrack::app {

class VideoFileSource final : public FrameSource {
 public:
  explicit VideoFileSource(const std::filesystem::path& file);

  std::optional<Frame> next() override;
  std::optional<int> frameCount() const override;
  double fps() const override { return fps_; }
  bool seekable() const override { return true; }
  void seek(int index) override;
  std::string description() const override;

 private:
  std::filesystem::path file_;
  cv::VideoCapture capture_;
  double fps_ = 30.0;
  int count_ = 0;  // 0 when the container does not say
  int nextIndex_ = 0;
};

}  // namespace reftrack::app
