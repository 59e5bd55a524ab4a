#pragma once
// RotationHomographyEstimator: the robust homography of a calibrated camera that only rotates
// about its centre (or sees a distant scene), H = K R K^-1 (SPEC §5) — 3 unknowns instead of 8.
// It stays well posed when the matches cover only a sliver of the image (a wide pan), where a
// general homography is pinned down along the sliver only and extrapolates wildly beyond it.
// RANSAC over 2-match samples (the rotation taking two reference bearings onto two frame
// bearings) with the RansacParams' iteration cap, early accept, inlier threshold, minimum inliers
// and progressive sampling; then the least-squares rotation of all inliers (Kabsch on the
// bearings), re-estimated until the inlier set is stable.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "engine/config/RansacParams.hpp"
#include "engine/homography/RobustHomographyEstimator.hpp"

namespace reftrack {

class RotationHomographyEstimator {
 public:
  // K: the camera's intrinsics (the same camera for both images). Throws reftrack::Error on a
  // non-invertible K or bad params.
  RotationHomographyEstimator(const Eigen::Matrix3d& K, RansacParams params = {});

  // As RobustHomographyEstimator::estimate (same inputs, same failure rules); H is K R K^-1.
  HomographyEstimate estimate(const std::vector<cv::Point2f>& src,
                              const std::vector<cv::Point2f>& dst, cv::Size imageSize,
                              const std::vector<float>& quality = {}) const;

  const RansacParams& params() const { return params_; }

 private:
  Eigen::Matrix3d K_, Kinv_;
  RansacParams params_;
};

// The rotation R (det +1) minimising sum |b_i - R a_i|^2 over the listed unit vectors (Kabsch);
// two non-parallel pairs determine it.
Eigen::Matrix3d bestRotation(const std::vector<Eigen::Vector3d>& a,
                             const std::vector<Eigen::Vector3d>& b,
                             const std::vector<int>& indices);

}  // namespace reftrack
