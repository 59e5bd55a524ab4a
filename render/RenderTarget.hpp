#pragma once
// RenderTarget: an off-screen framebuffer object with an RGBA8 colour buffer and a 24-bit depth
// buffer, read back as OpenCV images (row 0 = top of the image). Needs a current GL context.
#include <opencv2/core.hpp>

namespace reftrack::render {

class RenderTarget {
 public:
  // Throws reftrack::Error if the size is empty or beyond GL_MAX_RENDERBUFFER_SIZE.
  explicit RenderTarget(cv::Size size);
  ~RenderTarget();
  RenderTarget(const RenderTarget&) = delete;
  RenderTarget& operator=(const RenderTarget&) = delete;

  // Binds the framebuffer for drawing and sets the viewport to the whole target.
  void bind() const;
  cv::Size size() const { return size_; }
  unsigned int framebuffer() const { return framebuffer_; }

  // The colour buffer as CV_8UC3 BGR.
  cv::Mat readColourBgr() const;
  // Camera-frame depth z in metres per pixel (CV_32F), 0 where nothing was drawn; nearPlane and
  // farPlane must be those of the projection used to draw.
  cv::Mat readDepthMetres(double nearPlane, double farPlane) const;

 private:
  cv::Size size_;
  unsigned int framebuffer_ = 0, colour_ = 0, depth_ = 0;
};

}  // namespace reftrack::render
