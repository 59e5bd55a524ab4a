#include "app/research/baselines/PerFramePnpPeer.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <opencv2/calib3d.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack::app {

namespace {

std::vector<cv::Point2f> undistortedKeypoints(const PinholeCamera& camera,
                                              const std::vector<cv::KeyPoint>& keypoints) {
  std::vector<cv::Point2f> pixels;
  pixels.reserve(keypoints.size());
  for (const cv::KeyPoint& k : keypoints) pixels.push_back(k.pt);
  return camera.undistortPixels(pixels);
}

cv::Matx34d projectionMatrix(const PinholeCamera& camera, const RigidPose& worldToCamera) {
  const Eigen::Matrix<double, 3, 4> P = camera.K() * worldToCamera.matrix3x4();
  cv::Matx34d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out(r, c) = P(r, c);
  return out;
}

// Nearest neighbour of each query row among the train rows when it passes Lowe's ratio test.
std::vector<cv::DMatch> ratioMatches(const cv::BFMatcher& matcher, const cv::Mat& query,
                                     const cv::Mat& train, float ratio) {
  std::vector<cv::DMatch> out;
  if (query.empty() || train.rows < 2) return out;
  std::vector<std::vector<cv::DMatch>> knn;
  matcher.knnMatch(query, train, knn, 2);
  for (const std::vector<cv::DMatch>& m : knn)
    if (m.size() == 2 && m[0].distance < ratio * m[1].distance) out.push_back(m[0]);
  return out;
}

}  // namespace

PerFramePnpPeer::PerFramePnpPeer(const std::string& detector, const PinholeCamera& camera,
                                 const std::vector<cv::Mat>& referenceImages,
                                 const std::vector<RigidPose>& referencePoses,
                                 PerFramePnpPeerParams params)
    : detectorName_(detector),
      camera_(camera),
      params_(params),
      features_(openCvFeatures(detector, params.orbFeatures)) {
  if (referenceImages.size() < 2 || referenceImages.size() != referencePoses.size())
    throw Error("per-frame PnP peer: " + std::to_string(referenceImages.size()) + " images and " +
                std::to_string(referencePoses.size()) +
                " poses; two or more references with one pose each are needed");
  ransacErrorPx_ = params_.ransacErrorPxAt640x480 * resolutionScale(camera_.imageSize()) /
                   resolutionScale(cv::Size(640, 480));
  std::vector<std::vector<cv::Point2f>> undistorted;
  for (std::size_t r = 0; r < referenceImages.size(); ++r) {
    const cv::Mat& image = referenceImages[r];
    if (image.size() != camera_.imageSize())
      throw Error("per-frame PnP peer: reference " + std::to_string(r) + " is " +
                  std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                  ", the camera's images " + std::to_string(camera_.imageSize().width) + "x" +
                  std::to_string(camera_.imageSize().height));
    Reference ref;
    features_.detector->detectAndCompute(toGray8(image), cv::noArray(), ref.keypoints,
                                         ref.descriptors);
    ref.point.assign(ref.keypoints.size(), -1);
    undistorted.push_back(undistortedKeypoints(camera_, ref.keypoints));
    references_.push_back(std::move(ref));
  }
  const cv::BFMatcher matcher(features_.norm);
  for (std::size_t a = 0; a < references_.size(); ++a)
    for (std::size_t b = a + 1; b < references_.size(); ++b) {
      Reference &A = references_[a], &B = references_[b];
      std::vector<cv::DMatch> candidates =
          ratioMatches(matcher, A.descriptors, B.descriptors, params_.ratioTest);
      std::sort(candidates.begin(), candidates.end(),
                [](const cv::DMatch& x, const cv::DMatch& y) { return x.distance < y.distance; });
      // One point per keypoint: a keypoint of B that several of A's chose goes to the closest, and
      // a keypoint triangulated with an earlier pair keeps that point.
      std::vector<cv::DMatch> matches;
      std::vector<bool> taken(B.keypoints.size(), false);
      for (const cv::DMatch& m : candidates) {
        const auto inA = static_cast<std::size_t>(m.queryIdx);
        const auto inB = static_cast<std::size_t>(m.trainIdx);
        if (A.point[inA] >= 0 || B.point[inB] >= 0 || taken[inB]) continue;
        taken[inB] = true;
        matches.push_back(m);
      }
      if (matches.empty()) continue;
      cv::Mat_<double> pa(2, static_cast<int>(matches.size())),
          pb(2, static_cast<int>(matches.size()));
      for (std::size_t i = 0; i < matches.size(); ++i) {
        const cv::Point2f ua = undistorted[a][static_cast<std::size_t>(matches[i].queryIdx)];
        const cv::Point2f ub = undistorted[b][static_cast<std::size_t>(matches[i].trainIdx)];
        const int c = static_cast<int>(i);
        pa(0, c) = ua.x, pa(1, c) = ua.y, pb(0, c) = ub.x, pb(1, c) = ub.y;
      }
      cv::Mat homogeneous;
      cv::triangulatePoints(projectionMatrix(camera_, referencePoses[a]),
                            projectionMatrix(camera_, referencePoses[b]), pa, pb, homogeneous);
      homogeneous.convertTo(homogeneous, CV_64F);
      for (std::size_t i = 0; i < matches.size(); ++i) {
        const int c = static_cast<int>(i);
        const double w = homogeneous.at<double>(3, c);
        if (!(std::abs(w) > 0)) continue;
        const Eigen::Vector3d X(homogeneous.at<double>(0, c) / w, homogeneous.at<double>(1, c) / w,
                                homogeneous.at<double>(2, c) / w);
        const auto reprojects = [&](const RigidPose& pose, double x, double y) {
          const Eigen::Vector3d Xc = pose * X;
          if (!(Xc.z() > 0)) return false;  // behind the camera (or NaN)
          const Eigen::Vector2d p = camera_.project(Xc);
          return std::hypot(p.x() - x, p.y() - y) <= params_.maxTriangulationErrorPx;
        };
        const bool kept = X.allFinite() && reprojects(referencePoses[a], pa(0, c), pa(1, c)) &&
                          reprojects(referencePoses[b], pb(0, c), pb(1, c));
        if (!kept) continue;
        A.point[static_cast<std::size_t>(matches[i].queryIdx)] = static_cast<int>(points_.size());
        B.point[static_cast<std::size_t>(matches[i].trainIdx)] = static_cast<int>(points_.size());
        points_.emplace_back(X.x(), X.y(), X.z());
      }
    }
  if (points_.size() < 6)
    throw Error("per-frame PnP peer (" + detector + "): " + std::to_string(points_.size()) +
                " points triangulated from the references, fewer than the 6 PnP needs");
}

std::string perFramePnpPeerName(const std::string& detector) {
  std::string name;
  for (char c : detector) name += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return name + "+PnP";
}

std::string PerFramePnpPeer::noPoseReason(const PerFramePnpResult& result) const {
  return result.matches < params_.minInliers ? "too few 2D-3D matches" : "too few PnP inliers";
}

int PerFramePnpPeer::referencePoints(int r) const {
  int n = 0;
  for (int p : references_.at(static_cast<std::size_t>(r)).point) n += p >= 0 ? 1 : 0;
  return n;
}

PerFramePnpResult PerFramePnpPeer::locate(const cv::Mat& frame) const {
  if (frame.size() != camera_.imageSize())
    throw Error("per-frame PnP peer: the frame is " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + ", the camera's images " +
                std::to_string(camera_.imageSize().width) + "x" +
                std::to_string(camera_.imageSize().height));
  PerFramePnpResult result;
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  features_.detector->detectAndCompute(toGray8(frame), cv::noArray(), keypoints, descriptors);
  result.keypoints = static_cast<int>(keypoints.size());
  if (keypoints.empty()) return result;
  // Each frame keypoint's best ratio-test match over the references that leads to a 3D point.
  std::map<int, std::pair<float, int>> best;  // frame keypoint -> (distance, point)
  const cv::BFMatcher matcher(features_.norm);
  for (const Reference& ref : references_)
    for (const cv::DMatch& m :
         ratioMatches(matcher, descriptors, ref.descriptors, params_.ratioTest)) {
      const int point = ref.point[static_cast<std::size_t>(m.trainIdx)];
      if (point < 0) continue;
      const auto it = best.find(m.queryIdx);
      if (it == best.end() || m.distance < it->second.first) best[m.queryIdx] = {m.distance, point};
    }
  result.matches = static_cast<int>(best.size());
  if (result.matches < std::max(6, params_.minInliers)) return result;
  const std::vector<cv::Point2f> undistorted = undistortedKeypoints(camera_, keypoints);
  std::vector<cv::Point3d> object;
  std::vector<cv::Point2d> image;
  for (const auto& [keypoint, match] : best) {
    object.push_back(points_[static_cast<std::size_t>(match.second)]);
    image.emplace_back(undistorted[static_cast<std::size_t>(keypoint)]);
  }
  const cv::Mat K(camera_.Kcv());
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  if (!cv::solvePnPRansac(object, image, K, cv::noArray(), rvec, tvec, false,
                          params_.ransacIterations, static_cast<float>(ransacErrorPx_),
                          params_.ransacConfidence, inliers))
    return result;
  result.inliers = static_cast<int>(inliers.size());
  if (result.inliers < params_.minInliers) return result;
  std::vector<cv::Point3d> inlierObject;
  std::vector<cv::Point2d> inlierImage;
  for (int i : inliers) {
    inlierObject.push_back(object[static_cast<std::size_t>(i)]);
    inlierImage.push_back(image[static_cast<std::size_t>(i)]);
  }
  cv::solvePnPRefineLM(inlierObject, inlierImage, K, cv::noArray(), rvec, tvec);
  const Eigen::Vector3d r(rvec.at<double>(0), rvec.at<double>(1), rvec.at<double>(2));
  const Eigen::Vector3d t(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  const RigidPose pose(rotationFromAxisAngle(r), t);
  if (pose.allFinite()) result.worldToCamera = pose;
  return result;
}

}  // namespace reftrack::app
