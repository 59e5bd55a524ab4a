#include "app/simulator/DistortingLens.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

// Frame buffers of common GL implementations (OSMesa, Mesa EGL) hold up to 16384 pixels a side.
constexpr int kMaxCanvasSide = 16384;
// A point that re-distorts farther than this from its pixel has no pre-image (the lens folds).
constexpr double kRoundTripTolerancePx = 1e-3;

std::string coefficients(const PinholeCamera& camera) {
  std::ostringstream text;
  for (std::size_t i = 0; i < camera.distortion().size(); ++i)
    text << (i ? "," : "") << camera.distortion()[i];
  return text.str();
}

// Pixel positions of an s x s sub-pixel grid over the image (sub-pixel (i, j) of the
// supersampled image is at u = (i - (s-1)/2) / s: render::supersampledK's convention).
std::vector<cv::Point2f> subPixelGrid(cv::Size size, int s) {
  std::vector<cv::Point2f> grid;
  grid.reserve(static_cast<std::size_t>(size.area()) * static_cast<std::size_t>(s * s));
  const double offset = 0.5 * (s - 1);
  for (int j = 0; j < size.height * s; ++j)
    for (int i = 0; i < size.width * s; ++i)
      grid.emplace_back(static_cast<float>((i - offset) / s), static_cast<float>((j - offset) / s));
  return grid;
}

// Largest distance between a pixel and the re-distortion of its undistorted position.
double worstRoundTripPx(const PinholeCamera& camera, const std::vector<cv::Point2f>& pixels,
                        const std::vector<cv::Point2f>& undistorted) {
  const Eigen::Matrix3d& K = camera.K();
  std::vector<cv::Point3d> rays;
  rays.reserve(undistorted.size());
  for (const cv::Point2f& p : undistorted) {
    const double y = (p.y - K(1, 2)) / K(1, 1);
    rays.emplace_back((p.x - K(0, 2) - K(0, 1) * y) / K(0, 0), y, 1.0);
  }
  std::vector<cv::Point2d> back;
  cv::projectPoints(rays, cv::Vec3d::all(0), cv::Vec3d::all(0), camera.Kcv(), camera.distortion(),
                    back);
  double worst = 0.0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    const double d = std::hypot(back[i].x - pixels[i].x, back[i].y - pixels[i].y);
    if (!(d <= worst)) worst = d;  // NaN counts as the worst
  }
  return worst;
}

}  // namespace

DistortingLens::DistortingLens(const PinholeCamera& camera, int supersample)
    : size_(camera.imageSize()), supersample_(supersample) {
  if (!camera.hasDistortion()) throw Error("lens: the camera has no distortion to render");
  if (supersample < 1) throw Error("lens: supersample must be >= 1");
  const int s = supersample;
  const std::vector<cv::Point2f> fine = subPixelGrid(size_, s);
  const std::vector<cv::Point2f> fineIdeal = camera.undistortPixels(fine);
  const std::vector<cv::Point2f> coarse = subPixelGrid(size_, 1);
  const std::vector<cv::Point2f> coarseIdeal = camera.undistortPixels(coarse);
  // The pixel centres and the outermost sub-pixels (the image corners) must all invert.
  const double worst = std::max(worstRoundTripPx(camera, coarse, coarseIdeal),
                                worstRoundTripPx(camera, fine, fineIdeal));
  if (!(worst <= kRoundTripTolerancePx))
    throw Error("lens: distortion " + coefficients(camera) + " cannot be inverted over the whole " +
                std::to_string(size_.width) + "x" + std::to_string(size_.height) +
                " image (it folds back near the corners); use a smaller field of view or "
                "smaller coefficients");

  float minX = fineIdeal[0].x, maxX = minX, minY = fineIdeal[0].y, maxY = minY;
  for (const cv::Point2f& p : fineIdeal) {
    minX = std::min(minX, p.x);
    maxX = std::max(maxX, p.x);
    minY = std::min(minY, p.y);
    maxY = std::max(maxY, p.y);
  }
  // Two pixels of margin keep every bilinear neighbour on the canvas.
  const double left = std::floor(minX) - 2.0, top = std::floor(minY) - 2.0;
  idealSize_ = cv::Size(static_cast<int>(std::ceil(maxX) + 2.0 - left) + 1,
                        static_cast<int>(std::ceil(maxY) + 2.0 - top) + 1);
  if (idealSize_.width * s > kMaxCanvasSide || idealSize_.height * s > kMaxCanvasSide)
    throw Error("lens: the undistorted canvas (" + std::to_string(idealSize_.width) + "x" +
                std::to_string(idealSize_.height) + " at " + std::to_string(s) +
                "x supersampling) exceeds " + std::to_string(kMaxCanvasSide) +
                " pixels a side; use a smaller image, field of view or distortion");
  idealK_ = camera.K();
  idealK_(0, 2) -= left;
  idealK_(1, 2) -= top;

  const double offset = 0.5 * (s - 1);
  mapSupersampled_.create(size_.height * s, size_.width * s, CV_32FC2);
  for (int j = 0, n = 0; j < mapSupersampled_.rows; ++j)
    for (int i = 0; i < mapSupersampled_.cols; ++i, ++n) {
      const cv::Point2f& p = fineIdeal[static_cast<std::size_t>(n)];
      mapSupersampled_.at<cv::Vec2f>(j, i) =
          cv::Vec2f(static_cast<float>((p.x - left) * s + offset),
                    static_cast<float>((p.y - top) * s + offset));
    }
  mapDepth_.create(size_, CV_32FC2);
  for (int j = 0, n = 0; j < size_.height; ++j)
    for (int i = 0; i < size_.width; ++i, ++n) {
      const cv::Point2f& p = coarseIdeal[static_cast<std::size_t>(n)];
      mapDepth_.at<cv::Vec2f>(j, i) =
          cv::Vec2f(static_cast<float>(p.x - left), static_cast<float>(p.y - top));
    }
}

cv::Mat DistortingLens::distortSupersampled(const cv::Mat& ideal) const {
  if (ideal.size() != cv::Size(idealSize_.width * supersample_, idealSize_.height * supersample_))
    throw Error("lens: the ideal image has the wrong size");
  cv::Mat fine;
  cv::remap(ideal, fine, mapSupersampled_, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  if (supersample_ == 1) return fine;
  cv::Mat out;
  cv::resize(fine, out, size_, 0, 0, cv::INTER_AREA);
  return out;
}

cv::Mat DistortingLens::distortDepth(const cv::Mat& idealDepth) const {
  if (idealDepth.size() != idealSize_) throw Error("lens: the ideal depth has the wrong size");
  cv::Mat out;
  cv::remap(idealDepth, out, mapDepth_, cv::noArray(), cv::INTER_NEAREST, cv::BORDER_CONSTANT,
            cv::Scalar(0));
  return out;
}

}  // namespace reftrack::app
