#include "engine/reference/MarkerPoseEstimator.hpp"

#include <cmath>
#include <opencv2/aruco.hpp>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "engine/core/Error.hpp"
#include "engine/geometry/FrameUndistorter.hpp"
#include "engine/geometry/PixelDistortion.hpp"

namespace reftrack {

void MarkerPoseParams::check() const {
  if (!(std::isfinite(ambiguityRatio) && ambiguityRatio >= 1.0))
    throw Error("MarkerPoseEstimator.ambiguityRatio must be >= 1");
  if (!(std::isfinite(maxReprojectionRmsPx) && maxReprojectionRmsPx > 0.0))
    throw Error("MarkerPoseEstimator.maxReprojectionRmsPx must be positive");
}

MarkerPoseEstimator::MarkerPoseEstimator(MarkerSpec marker, PinholeCamera camera, Params params)
    : marker_(std::move(marker)), camera_(std::move(camera)), params_(params) {
  marker_.check();
  camera_.check();
  params_.check();
}

MarkerPose MarkerPoseEstimator::estimate(const cv::Mat& image, const std::string& imageName) const {
  if (image.empty()) throw Error("image '" + imageName + "' is empty or unreadable");
  if (image.size() != camera_.imageSize()) {
    std::ostringstream ss;
    ss << "image '" << imageName << "' is " << image.cols << "x" << image.rows
       << " but the camera is calibrated for " << camera_.imageSize().width << "x"
       << camera_.imageSize().height;
    throw Error(ss.str());
  }
  cv::Mat gray;
  if (image.channels() == 3)
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  else if (image.channels() == 4)
    cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY);
  else
    gray = image;

  auto dictionary = cv::aruco::getPredefinedDictionary(marker_.dictionaryEnum());
  auto detector = cv::aruco::DetectorParameters::create();
  detector->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  detector->cornerRefinementWinSize = 5;
  detector->cornerRefinementMinAccuracy = 0.01;
  detector->cornerRefinementMaxIterations = 50;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(gray, dictionary, corners, ids, detector);

  int found = -1, count = 0;
  for (size_t i = 0; i < ids.size(); ++i)
    if (ids[i] == marker_.id) {
      found = static_cast<int>(i);
      ++count;
    }
  if (count == 0) {
    std::ostringstream ss;
    ss << "marker " << marker_.toString() << " not found in image '" << imageName << "'";
    if (!ids.empty()) {
      ss << " (markers seen:";
      for (int id : ids) ss << ' ' << id;
      ss << ")";
    }
    throw Error(ss.str());
  }
  if (count > 1)
    throw Error("marker id " + std::to_string(marker_.id) + " appears " + std::to_string(count) +
                " times in image '" + imageName + "': the world frame is ambiguous");

  // Pose from undistorted corners with the ideal K (distortion is removed from coordinates).
  std::array<cv::Point2f, 4> detected;
  for (int k = 0; k < 4; ++k) detected[k] = corners[found][k];
  // The refinement fits a straight line to each side of the marker, and a lens bends them: with
  // distortion it runs on the undistorted image (FrameUndistorter), whose corners are already
  // ideal. (Simulator, k1 = -0.3, 50 degrees: refining on the recorded image put reference A's
  // centre 3.6 mm off.)
  std::vector<cv::Point2f> ideal;
  if (camera_.hasDistortion()) {
    const std::vector<cv::Point2f> start =
        camera_.undistortPixels(std::vector<cv::Point2f>(detected.begin(), detected.end()));
    std::array<cv::Point2f, 4> startIdeal;
    for (int k = 0; k < 4; ++k) startIdeal[k] = start[static_cast<std::size_t>(k)];
    const std::array<cv::Point2f, 4> refined =
        refineMarkerCorners(FrameUndistorter(camera_).undistort(gray), startIdeal);
    ideal.assign(refined.begin(), refined.end());
  } else {
    const std::array<cv::Point2f, 4> refined = refineMarkerCorners(gray, detected);
    ideal.assign(refined.begin(), refined.end());
  }
  // The corners in the recorded image (the ideal ones without distortion).
  const std::vector<cv::Point2f> pixels = distortPixels(camera_, ideal);
  std::vector<cv::Point3f> object;
  for (const Eigen::Vector3d& c : marker_.cornersWorld())
    object.emplace_back(static_cast<float>(c.x()), static_cast<float>(c.y()),
                        static_cast<float>(c.z()));
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat errors;
  const cv::Matx33d K = camera_.Kcv();
  cv::solvePnPGeneric(object, ideal, K, cv::noArray(), rvecs, tvecs, false,
                      cv::SOLVEPNP_IPPE_SQUARE, cv::noArray(), cv::noArray(), errors);
  if (rvecs.empty()) throw Error("marker pose could not be solved in image '" + imageName + "'");

  MarkerPose result;
  std::vector<double> rms;
  std::vector<RigidPose> poses;
  for (size_t s = 0; s < rvecs.size(); ++s) {
    cv::Mat rvec = rvecs[s].clone(), tvec = tvecs[s].clone();
    cv::solvePnPRefineLM(object, ideal, K, cv::noArray(), rvec, tvec);
    cv::Matx33d Rcv;
    cv::Rodrigues(rvec, Rcv);
    Eigen::Matrix3d R;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) R(r, c) = Rcv(r, c);
    const RigidPose pose(
        R, Eigen::Vector3d(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2)));
    double sum = 0.0;
    const auto world = marker_.cornersWorld();
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector2d p = camera_.project(pose, world[k]);
      sum += (p - Eigen::Vector2d(ideal[k].x, ideal[k].y)).squaredNorm();
    }
    rms.push_back(std::sqrt(sum / 4.0));
    poses.push_back(pose);
  }
  const size_t best = (rms.size() > 1 && rms[1] < rms[0]) ? 1 : 0;
  result.worldToCamera = poses[best];
  result.reprojectionRmsPx = rms[best];
  result.alternativeRmsPx = rms.size() > 1 ? rms[1 - best] : INFINITY;
  for (int k = 0; k < 4; ++k) result.cornersPixels[k] = pixels[k];

  if (result.worldToCamera.translation().z() <= 0.0)
    throw Error("marker in image '" + imageName + "' solves to a pose behind the camera");
  if (result.reprojectionRmsPx > params_.maxReprojectionRmsPx) {
    std::ostringstream ss;
    ss << "marker corners in image '" << imageName << "' reproject with "
       << result.reprojectionRmsPx << " px RMS (limit " << params_.maxReprojectionRmsPx
       << "): wrong camera calibration or marker side length?";
    throw Error(ss.str());
  }
  // A flip whose corners fit as well is indistinguishable: refuse rather than guess. The floor
  // of 0.05 px keeps noise-free synthetic corners from being called ambiguous.
  if (result.alternativeRmsPx < params_.ambiguityRatio * std::max(result.reprojectionRmsPx, 0.05)) {
    const double angle =
        RigidPose::rotationDistance(poses[0], poses.size() > 1 ? poses[1] : poses[0]);
    if (angle > 1.0 * M_PI / 180.0) {
      std::ostringstream ss;
      ss << "marker pose in image '" << imageName << "' is ambiguous: two poses "
         << angle * 180 / M_PI << " degrees apart fit the corners equally well ("
         << result.reprojectionRmsPx << " vs " << result.alternativeRmsPx
         << " px); photograph the marker less frontally or from closer";
      throw Error(ss.str());
    }
  }
  return result;
}

std::array<cv::Point2f, 4> refineMarkerCorners(const cv::Mat& gray,
                                               const std::array<cv::Point2f, 4>& initial) {
  // cornerSubPix (aruco's refinement) is biased by ~0.2 px on the convex corners of a marker's
  // outer square (measured on exactly rendered markers). Each side of that square is a straight
  // edge: locate it at its 50% grey crossing along the normal at many points (unbiased for any
  // symmetric blur), fit a line per side, and intersect neighbouring sides.
  cv::Mat img;
  gray.convertTo(img, CV_32F);
  const auto sample = [&](cv::Point2f p) {
    const int x0 = static_cast<int>(std::floor(p.x)), y0 = static_cast<int>(std::floor(p.y));
    if (x0 < 0 || y0 < 0 || x0 + 1 >= img.cols || y0 + 1 >= img.rows) return -1.0f;
    const float ax = p.x - x0, ay = p.y - y0;
    const float* r0 = img.ptr<float>(y0);
    const float* r1 = img.ptr<float>(y0 + 1);
    return (1 - ay) * ((1 - ax) * r0[x0] + ax * r0[x0 + 1]) +
           ay * ((1 - ax) * r1[x0] + ax * r1[x0 + 1]);
  };
  const cv::Point2f centre = (initial[0] + initial[1] + initial[2] + initial[3]) * 0.25f;
  std::array<cv::Vec4f, 4> lines;
  for (int k = 0; k < 4; ++k) {
    const cv::Point2f a = initial[k], b = initial[(k + 1) % 4];
    const float length = static_cast<float>(cv::norm(b - a));
    if (length < 8.0f) return initial;
    const cv::Point2f dir = (b - a) / length;
    cv::Point2f normal(-dir.y, dir.x);
    if (normal.dot((a + b) * 0.5f - centre) < 0) normal = -normal;  // outward
    // Profile half-length: well inside the one-module black border, and into the quiet zone.
    const float reach = std::clamp(length / 16.0f, 2.0f, 6.0f), step = 0.05f;
    std::vector<cv::Point2f> edgePoints;
    const int samples = std::max(8, static_cast<int>(length / 2));
    for (int i = 1; i < samples; ++i) {
      const float t = 0.15f + 0.7f * i / samples;  // keep clear of the corners
      const cv::Point2f p = a + (b - a) * t;
      std::vector<float> profile;
      for (float s = -reach; s <= reach + 1e-4f; s += step)
        profile.push_back(sample(p + normal * s));
      if (*std::min_element(profile.begin(), profile.end()) < 0) continue;
      const int n = static_cast<int>(profile.size()), ends = std::max(1, n / 8);
      float inside = 0, outside = 0;
      for (int j = 0; j < ends; ++j) {
        inside += profile[j];
        outside += profile[n - 1 - j];
      }
      inside /= ends;
      outside /= ends;
      if (outside - inside < 20.0f) continue;  // no clear black-to-white edge here
      const float mid = 0.5f * (inside + outside);
      for (int j = 0; j + 1 < n; ++j)
        if (profile[j] < mid && profile[j + 1] >= mid) {
          const float f = (mid - profile[j]) / (profile[j + 1] - profile[j]);
          edgePoints.push_back(p + normal * (-reach + (j + f) * step));
          break;
        }
    }
    if (edgePoints.size() < 5) return initial;
    cv::fitLine(edgePoints, lines[k], cv::DIST_HUBER, 0, 0.01, 0.01);
  }
  std::array<cv::Point2f, 4> out;
  for (int k = 0; k < 4; ++k) {
    // Corner k joins side k-1 (from corner k-1 to k) and side k (from corner k to k+1).
    const cv::Vec4f& l1 = lines[(k + 3) % 4];
    const cv::Vec4f& l2 = lines[k];
    const float det = l1[0] * (-l2[1]) - l1[1] * (-l2[0]);
    if (std::abs(det) < 1e-6f) return initial;
    const float dx = l2[2] - l1[2], dy = l2[3] - l1[3];
    const float s = (dx * (-l2[1]) - dy * (-l2[0])) / det;
    out[k] = cv::Point2f(l1[2] + s * l1[0], l1[3] + s * l1[1]);
    if (cv::norm(out[k] - initial[k]) > 2.0) return initial;  // went astray
  }
  return out;
}

}  // namespace reftrack
