#pragma once
// SupportRegion: the part of an image that a registered homography is known to explain — the
// convex hull of the image positions of its inlier correspondences (keypoint or corner matches),
// widened by a margin. On a scene that is only partly the plane (a facade among trees, people,
// sky and other facades), the refinement and the registration check judge H there rather than
// over the whole view. An empty region stands for the whole image.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

class SupportRegion {
 public:
  SupportRegion() = default;  // the whole image
  // points: the inliers' positions in the image (pixels); margin: the hull is widened by this
  // many pixels. No point: the whole image; one or two points, or points on a line: the
  // points' margin only.
  SupportRegion(const std::vector<cv::Point2f>& points, double margin);

  bool whole() const { return hull_.empty(); }
  // True for every point of the whole image.
  bool contains(cv::Point2f p) const;
  // The same region in an image scaled by f (a pyramid level: f = 2^-level, positions scaled as
  // ImagePyramid::levelToImage does).
  SupportRegion scaled(double f) const;
  // The hull's area (pixels, margin not included; 0 for the whole image).
  double hullArea() const { return area_; }
  const std::vector<cv::Point2f>& hull() const { return hull_; }
  double margin() const { return margin_; }

 private:
  std::vector<cv::Point2f> hull_;
  double margin_ = 0.0;
  double area_ = 0.0;
};

// The margin used for an image of `size`: this fraction of its diagonal (about one cell of the
// registration check's 16 x 12 grid: a point just outside the outermost inliers still counts).
double supportMargin(cv::Size size);

}  // namespace reftrack
