#include "app/baselines/OrbPnpRelocaliser.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

OrbPnpRelocaliser::OrbPnpRelocaliser(const MultiReferenceMap& map, OrbPnpRelocaliserParams params)
    : params_(params), K_(map.camera.Kcv()), dist_(map.camera.distortion()) {
  if (map.keypointKind != "orb")
    throw Error("ORB + PnP baseline: the map's keypoint layer is '" + map.keypointKind +
                "', not 'orb'");
  for (const ReferenceView& v : map.views)
    for (std::size_t k = 0; k < v.keypoints.keypoints.size(); ++k) {
      const Eigen::Vector3d& X = v.keypoints.points[k];
      if (!X.allFinite()) continue;
      points_.emplace_back(static_cast<float>(X.x()), static_cast<float>(X.y()),
                           static_cast<float>(X.z()));
      descriptors_.push_back(v.keypoints.descriptors.row(static_cast<int>(k)));
    }
  if (points_.empty()) throw Error("ORB + PnP baseline: the map's keypoints have no 3D points");
  const cv::Size size = map.camera.imageSize();
  const double area = static_cast<double>(size.area()) / (640.0 * 480.0);
  orb_ = cv::ORB::create(std::max(1, static_cast<int>(params_.features * area + 0.5)));
}

std::optional<RigidPose> OrbPnpRelocaliser::locate(const cv::Mat& frame) const {
  cv::Mat gray = frame;
  if (frame.channels() == 3) cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb_->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  if (descriptors.empty()) return std::nullopt;
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(descriptors, descriptors_, knn, 2);
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  for (const auto& m : knn)
    if (m.size() == 2 && m[0].distance < params_.ratioTest * m[1].distance) {
      object.push_back(points_[static_cast<std::size_t>(m[0].trainIdx)]);
      image.push_back(keypoints[static_cast<std::size_t>(m[0].queryIdx)].pt);
    }
  if (static_cast<int>(object.size()) < params_.minInliers) return std::nullopt;
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  // OpenCV's defaults: 100 iterations, 8 px, confidence 0.99, SOLVEPNP_ITERATIVE.
  if (!cv::solvePnPRansac(object, image, K_, dist_, rvec, tvec, false, 100, 8.0f, 0.99, inliers) ||
      static_cast<int>(inliers.size()) < params_.minInliers)
    return std::nullopt;
  Vector6d x;
  x << tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2), rvec.at<double>(0),
      rvec.at<double>(1), rvec.at<double>(2);
  return RigidPose::fromVector6(x);
}

}  // namespace reftrack::app
