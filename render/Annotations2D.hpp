#pragma once
// Annotations2D: 2-D overlay items in image pixel coordinates (pixel centres at integers, row 0
// at the top) drawn on top of everything in the current viewport: text labels (stb_easy_font,
// scalable, on a dark box), dots, segments (match lines), infinite lines a*x + b*y + c = 0
// clipped to the image (epipolar lines) and polylines; colour and thickness per item.
// Items accumulate until clear(). Needs a current GL 3.3 context.
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "render/PixelCanvas.hpp"

namespace reftrack::render {

// The part of the line a*x + b*y + c = 0 inside the image [-0.5, W-0.5] x [-0.5, H-0.5];
// nullopt when it misses the image or (a, b) = (0, 0).
std::optional<std::pair<cv::Point2d, cv::Point2d>> clipLineToImage(double a, double b, double c,
                                                                   cv::Size imageSize);

class Annotations2D {
 public:
  // Text whose top-left glyph corner is `topLeft`; glyphs are 7 px high per unit of `scale`.
  // With `box`, a translucent dark box (textBox) goes behind it.
  void addText(const cv::Point2f& topLeft, const std::string& text, const cv::Scalar& colourBgr,
               float scale = 2.0f, bool box = true);
  void addDot(const cv::Point2f& centre, float radius, const cv::Scalar& colourBgr);
  void addSegment(const cv::Point2f& from, const cv::Point2f& to, float thickness,
                  const cv::Scalar& colourBgr);
  // Returns false (and adds nothing) when the line misses the image.
  bool addInfiniteLine(double a, double b, double c, cv::Size imageSize, float thickness,
                       const cv::Scalar& colourBgr);
  void addPolyline(const std::vector<cv::Point2f>& points, bool closed, float thickness,
                   const cv::Scalar& colourBgr);
  void clear();
  bool empty() const { return canvas_.empty(); }

  // Draws all items over the current viewport, which shows an image of `imageSize` pixels.
  void draw(cv::Size imageSize);

  // The rectangle (pixel edges) covered by the box behind a label.
  static cv::Rect2f textBox(const cv::Point2f& topLeft, const std::string& text, float scale);

 private:
  PixelCanvas canvas_;
};

}  // namespace reftrack::render
