#pragma once
// VideoBackground: draws a camera frame (CV_8UC3 BGR or CV_8UC1 grey) over the whole current
// viewport, image row 0 at the top. Pixel-exact (nearest sampling) when the viewport has the
// image's size, bilinear when scaled. Depth is neither tested nor written. Needs a current
// GL 3.3 context.
#include <memory>
#include <opencv2/core.hpp>

namespace reftrack::render {

class VideoBackground {
 public:
  VideoBackground();
  ~VideoBackground();
  VideoBackground(const VideoBackground&) = delete;
  VideoBackground& operator=(const VideoBackground&) = delete;

  // Uploads `image` (same size as last time: in place) and draws it. Throws reftrack::Error for
  // an empty image or an unsupported pixel type.
  void draw(const cv::Mat& image);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::render
