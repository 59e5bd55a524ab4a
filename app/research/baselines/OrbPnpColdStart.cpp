#include "app/research/baselines/OrbPnpColdStart.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack::app {

OrbPnpColdStart::OrbPnpColdStart(const MultiReferenceMap& map, OrbPnpColdStartParams params)
    : params_(params), camera_(map.camera), orb_(cv::ORB::create(params.features)) {
  for (const ReferenceView& view : map.views) {
    const ReferenceKeypoints& layer = view.keypoints;
    if (layer.empty()) continue;
    if (layer.descriptors.type() != CV_8U || layer.descriptors.cols != 32)
      throw Error("ORB cold-start baseline: reference '" + view.name +
                  "' holds no ORB descriptors (map keypoints '" + map.keypointKind + "')");
    for (std::size_t i = 0; i < layer.keypoints.size(); ++i) {
      const Eigen::Vector3d& X = layer.points[i];
      if (!X.allFinite()) continue;
      modelPoints_.emplace_back(static_cast<float>(X.x()), static_cast<float>(X.y()),
                                static_cast<float>(X.z()));
      modelDescriptors_.push_back(layer.descriptors.row(static_cast<int>(i)));
    }
  }
  if (static_cast<int>(modelPoints_.size()) < params_.minInliers)
    throw Error("ORB cold-start baseline: the map holds " + std::to_string(modelPoints_.size()) +
                " keypoints with a 3D point, fewer than minInliers = " +
                std::to_string(params_.minInliers));
}

OrbPnpColdStartResult OrbPnpColdStart::locate(const cv::Mat& frame) const {
  cv::Mat gray = frame;
  if (frame.channels() == 3) cv::cvtColor(frame, gray, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb_->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  OrbPnpColdStartResult result;
  if (keypoints.empty()) return result;
  std::vector<std::vector<cv::DMatch>> knn;
  cv::BFMatcher(cv::NORM_HAMMING).knnMatch(descriptors, modelDescriptors_, knn, 2);
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  for (const auto& m : knn) {
    if (m.size() < 2 || m[0].distance >= params_.ratioTest * m[1].distance) continue;
    object.push_back(modelPoints_[static_cast<std::size_t>(m[0].trainIdx)]);
    image.push_back(keypoints[static_cast<std::size_t>(m[0].queryIdx)].pt);
  }
  result.matches = static_cast<int>(object.size());
  if (result.matches < std::max(6, params_.minInliers)) return result;
  cv::Mat K;
  cv::eigen2cv(camera_.K(), K);
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  const cv::Mat distortion(camera_.distortion(), true);
  if (!cv::solvePnPRansac(object, image, K, distortion, rvec, tvec, false, params_.ransacIterations,
                          params_.reprojectionErrorPx, params_.confidence, inliers))
    return result;
  result.inliers = static_cast<int>(inliers.size());
  if (result.inliers < params_.minInliers) return result;
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  Eigen::Matrix3d Re;
  cv::cv2eigen(cv::Mat(R), Re);
  result.worldToCamera =
      RigidPose(Re, Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
  return result;
}

}  // namespace reftrack::app
