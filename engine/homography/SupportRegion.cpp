#include "engine/homography/SupportRegion.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace reftrack {

namespace {

// One cell of a 16 x 12 grid is 1/20 of the diagonal.
constexpr double kMarginFraction = 0.05;

}  // namespace

double supportMargin(cv::Size size) {
  return kMarginFraction * std::hypot(static_cast<double>(size.width), size.height);
}

SupportRegion::SupportRegion(const std::vector<cv::Point2f>& points, double margin)
    : margin_(std::max(0.0, margin)) {
  if (points.empty()) return;  // no inliers given: the whole image
  cv::convexHull(points, hull_);
  if (hull_.size() >= 3) area_ = cv::contourArea(hull_);
}

bool SupportRegion::contains(cv::Point2f p) const {
  if (hull_.empty()) return true;
  if (hull_.size() >= 3) {
    // pointPolygonTest: positive inside, negative distance outside.
    const double d = cv::pointPolygonTest(hull_, p, true);
    return d >= -margin_;
  }
  // A point or a segment: within the margin of it.
  double best = 1e30;
  for (size_t i = 0; i < hull_.size(); ++i) {
    const cv::Point2f a = hull_[i], b = hull_[(i + 1) % hull_.size()];
    const cv::Point2f ab = b - a, ap = p - a;
    const double len = ab.dot(ab);
    const double t = len > 0 ? std::clamp(static_cast<double>(ap.dot(ab)) / len, 0.0, 1.0) : 0.0;
    const cv::Point2d q(a.x + t * ab.x, a.y + t * ab.y);
    best = std::min(best, std::hypot(p.x - q.x, p.y - q.y));
  }
  return best <= margin_;
}

SupportRegion SupportRegion::scaled(double f) const {
  SupportRegion out;
  if (hull_.empty()) return out;
  out.hull_ = hull_;
  // As ImagePyramid::levelToImage: level pixel u is full-resolution pixel 2^level u.
  for (cv::Point2f& p : out.hull_) p *= static_cast<float>(f);
  out.margin_ = margin_ * f;
  out.area_ = area_ * f * f;
  return out;
}

}  // namespace reftrack
