#pragma once
// PinholeCamera: intrinsics K, OpenCV distortion coefficients and the image size.
// Stored as camera.yml with the keys of OpenCV's calibration sample (image_width,
// image_height, camera_matrix, distortion_coefficients). Pixel centres are at integer
// coordinates (OpenCV convention): pixel (0,0) covers [-0.5, 0.5] x [-0.5, 0.5].
#include <Eigen/Core>
#include <filesystem>
#include <opencv2/core.hpp>
#include <vector>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

class PinholeCamera {
 public:
  PinholeCamera() = default;
  PinholeCamera(const Eigen::Matrix3d& K, cv::Size imageSize, std::vector<double> distortion = {});
  // From a horizontal field of view (degrees), principal point at the image centre.
  static PinholeCamera fromFieldOfView(cv::Size imageSize, double horizontalFovDeg);

  // Throws reftrack::Error naming the field at fault.
  static PinholeCamera load(const std::filesystem::path& file);
  void save(const std::filesystem::path& file) const;  // atomic (temp file + rename)
  // Throws reftrack::Error naming the bad field (size, focal length, NaN, ...).
  void check() const;

  const Eigen::Matrix3d& K() const { return K_; }
  cv::Matx33d Kcv() const;
  double fx() const { return K_(0, 0); }
  double fy() const { return K_(1, 1); }
  double cx() const { return K_(0, 2); }
  double cy() const { return K_(1, 2); }
  cv::Size imageSize() const { return size_; }
  const std::vector<double>& distortion() const { return dist_; }
  bool hasDistortion() const;

  // Ideal pinhole projection K * X / Z of a camera-frame point (no distortion).
  Eigen::Vector2d project(const Eigen::Vector3d& Xcam) const;
  // World point through a world->camera pose.
  Eigen::Vector2d project(const RigidPose& worldToCamera, const Eigen::Vector3d& Xworld) const {
    return project(worldToCamera * Xworld);
  }
  // Projection including lens distortion (as cv::projectPoints).
  Eigen::Vector2d projectDistorted(const Eigen::Vector3d& Xcam) const;
  // Removes distortion from pixel coordinates; results stay in pixels (K applied again).
  std::vector<cv::Point2f> undistortPixels(const std::vector<cv::Point2f>& pixels) const;

  // Same camera for an image resized by `scale` (K scaled about the pixel-centre convention).
  PinholeCamera scaled(double scale) const;

 private:
  Eigen::Matrix3d K_ = Eigen::Matrix3d::Identity();
  cv::Size size_{0, 0};
  std::vector<double> dist_;
};

}  // namespace reftrack
