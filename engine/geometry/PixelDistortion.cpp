#include "engine/geometry/PixelDistortion.hpp"

#include <opencv2/calib3d.hpp>

namespace reftrack {

std::vector<cv::Point2f> distortPixels(const PinholeCamera& camera,
                                       const std::vector<cv::Point2f>& idealPixels) {
  if (!camera.hasDistortion() || idealPixels.empty()) return idealPixels;
  const Eigen::Matrix3d& K = camera.K();
  std::vector<cv::Point3d> rays;
  rays.reserve(idealPixels.size());
  for (const cv::Point2f& p : idealPixels) {
    const double y = (p.y - K(1, 2)) / K(1, 1);
    rays.emplace_back((p.x - K(0, 2) - K(0, 1) * y) / K(0, 0), y, 1.0);
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(rays, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), camera.Kcv(), camera.distortion(),
                    projected);
  std::vector<cv::Point2f> out;
  out.reserve(projected.size());
  for (const cv::Point2d& p : projected)
    out.emplace_back(static_cast<float>(p.x), static_cast<float>(p.y));
  return out;
}

}  // namespace reftrack
