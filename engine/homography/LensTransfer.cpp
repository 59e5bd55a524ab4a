#include "engine/homography/LensTransfer.hpp"

#include <cmath>
#include <limits>

#include "engine/geometry/PixelDistortion.hpp"

namespace reftrack {

std::vector<cv::Point2d> transferThroughLens(const cv::Matx33d& H,
                                             const std::vector<cv::Point2d>& referencePixels,
                                             const PinholeCamera& camera,
                                             bool referenceThroughLens) {
  std::vector<cv::Point2f> ideal;
  ideal.reserve(referencePixels.size());
  for (const cv::Point2d& p : referencePixels)
    ideal.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
  if (referenceThroughLens) ideal = camera.undistortPixels(ideal);
  std::vector<cv::Point2f> mapped;
  std::vector<bool> valid;
  for (const cv::Point2f& p : ideal) {
    const cv::Vec3d q = H * cv::Vec3d(p.x, p.y, 1.0);
    const bool ok = q[2] > 0 && std::isfinite(q[0] / q[2]) && std::isfinite(q[1] / q[2]);
    valid.push_back(ok);
    mapped.emplace_back(ok ? static_cast<float>(q[0] / q[2]) : 0.0f,
                        ok ? static_cast<float>(q[1] / q[2]) : 0.0f);
  }
  const std::vector<cv::Point2f> distorted = distortPixels(camera, mapped);
  std::vector<cv::Point2d> out;
  out.reserve(distorted.size());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t i = 0; i < distorted.size(); ++i)
    out.push_back(valid[i] ? cv::Point2d(distorted[i]) : cv::Point2d(nan, nan));
  return out;
}

}  // namespace reftrack
