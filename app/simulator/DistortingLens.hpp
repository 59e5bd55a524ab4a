#pragma once
// DistortingLens: the simulator's lens stage. A camera with OpenCV radial-tangential distortion
// sees, at output pixel p, the ray an ideal pinhole camera (same fx, fy, skew) sees at the pixel
// undistort(p). The lens renders an ideal image on a canvas large enough to hold undistort(p) for
// every output pixel, then resamples it at those positions (cv::remap), so a world point X lands
// at cv::projectPoints(X) up to the resampling's interpolation. Supersampled: the map is
// computed for every sub-pixel of an s x s grid (pixel-centre convention as
// render::supersampledK) and the remapped image is area-averaged back down.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack::app {

class DistortingLens {
 public:
  // Throws reftrack::Error when the camera has no distortion, or when the distortion cannot be
  // inverted over the whole image (it folds back: a pixel re-distorts elsewhere), naming the
  // coefficients and what to change.
  DistortingLens(const PinholeCamera& camera, int supersample);

  // The ideal pinhole camera the scene is rendered with: K (principal point moved into the
  // canvas) and the canvas size, at 1x (multiply by supersample via render::supersampledK).
  const Eigen::Matrix3d& idealK() const { return idealK_; }
  cv::Size idealSize() const { return idealSize_; }
  int supersample() const { return supersample_; }

  // `ideal`: the ideal image rendered at supersample times idealSize() with
  // supersampledK(idealK(), supersample) (CV_8UC3). Returns the distorted image at the camera's
  // size, area-averaged from the supersampled remap (bilinear interpolation).
  cv::Mat distortSupersampled(const cv::Mat& ideal) const;
  // `idealDepth`: CV_32F at idealSize() (1x). Nearest-neighbour remap (a depth is never blended
  // across a surface edge), so each pixel holds the depth of the surface within 0.5 px of it.
  cv::Mat distortDepth(const cv::Mat& idealDepth) const;

 private:
  cv::Size size_;
  int supersample_ = 1;
  Eigen::Matrix3d idealK_ = Eigen::Matrix3d::Identity();
  cv::Size idealSize_;
  cv::Mat mapSupersampled_;  // CV_32FC2: supersampled output pixel -> supersampled ideal pixel
  cv::Mat mapDepth_;         // CV_32FC2: output pixel -> ideal pixel (1x)
};

}  // namespace reftrack::app
