#pragma once
// PixelCanvas: coloured 2-D triangles in image pixel coordinates (OpenCV convention: pixel
// centres at integers, row 0 at the top), mapped onto the whole current viewport and
// alpha-blended on top of everything (no depth test). The building block of wireframe
// overlays, point markers and annotations. Needs a current GL 3.3 context to draw.
#include <Eigen/Core>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack::render {

// cv::Scalar(b, g, r) in 0..255 plus an opacity in 0..1 to RGBA in 0..1.
Eigen::Vector4f rgbaFromBgr(const cv::Scalar& colourBgr, double alpha = 1.0);

class PixelCanvas {
 public:
  PixelCanvas();
  ~PixelCanvas();
  PixelCanvas(const PixelCanvas&) = delete;
  PixelCanvas& operator=(const PixelCanvas&) = delete;

  void addTriangle(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c,
                   const Eigen::Vector4f& rgba);
  void addQuad(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c,
               const Eigen::Vector2f& d, const Eigen::Vector4f& rgba);
  // A segment `width` pixels wide, with square caps reaching width/2 past each end.
  void addThickLine(const Eigen::Vector2f& from, const Eigen::Vector2f& to, float width,
                    const Eigen::Vector4f& rgba);
  // A filled disc (a 32-gon, point-symmetric about the centre).
  void addDisc(const Eigen::Vector2f& centre, float radius, const Eigen::Vector4f& rgba);
  bool empty() const;
  void clear();

  // Draws everything added so far over the current viewport, whose full extent shows an image
  // of `imageSize` pixels; keeps the geometry (call clear() for the next frame).
  void draw(cv::Size imageSize);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::render
