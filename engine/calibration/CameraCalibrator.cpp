#include "engine/calibration/CameraCalibrator.hpp"

#include <cmath>
#include <limits>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/config/ConfigValue.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

void CalibrationParams::check() const {
  requireIntInRange("calibration.min_views", minViews, 3, 100000);
  requireIntInRange("calibration.max_views", maxViews, minViews, 100000);
}

CameraCalibrator::CameraCalibrator(CalibrationBoard board, CalibrationParams params)
    : detector_(std::move(board)), params_(params) {
  params_.check();
}

void CameraCalibrator::checkImageSize(cv::Size size, const std::string& label) {
  if (size.area() == 0) throw Error("image '" + label + "' is empty");
  if (imageSize_.area() == 0) imageSize_ = size;
  if (size != imageSize_)
    throw Error("image '" + label + "' is " + std::to_string(size.width) + "x" +
                std::to_string(size.height) + " but the first image was " +
                std::to_string(imageSize_.width) + "x" + std::to_string(imageSize_.height));
}

bool CameraCalibrator::addImage(const cv::Mat& image, const std::string& label) {
  checkImageSize(image.size(), label);
  ++examined_;
  auto obs = detector_.detect(image);
  if (!obs) {
    rejected_.push_back(label);
    return false;
  }
  views_.push_back({label, std::move(*obs)});
  return true;
}

void CameraCalibrator::addObservation(BoardObservation observation, cv::Size imageSize,
                                      const std::string& label) {
  checkImageSize(imageSize, label);
  if (observation.imagePoints.size() != observation.objectPoints.size() ||
      observation.imagePoints.empty())
    throw Error("view '" + label + "': the board observation has no or mismatched corners");
  ++examined_;
  views_.push_back({label, std::move(observation)});
}

// Describes each view by where the board sits, how large it looks and how it is tilted (the
// board normal from the plane homography under a rough K with f = image width), then picks views
// greedily, each the farthest (in that descriptor) from those already picked.
std::vector<std::size_t> CameraCalibrator::selectSpreadViews() const {
  std::vector<std::size_t> all(views_.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  if (static_cast<int>(views_.size()) <= params_.maxViews) return all;

  const double w = imageSize_.width, h = imageSize_.height;
  const cv::Matx33d roughK(w, 0, 0.5 * (w - 1), 0, w, 0.5 * (h - 1), 0, 0, 1);
  std::vector<cv::Vec<double, 5>> descriptors;
  for (const View& v : views_) {
    const auto& img = v.observation.imagePoints;
    std::vector<cv::Point2f> plane;
    for (const auto& p : v.observation.objectPoints) plane.emplace_back(p.x, p.y);
    cv::Point2f centre(0, 0);
    for (const auto& p : img) centre += p;
    centre *= 1.0f / static_cast<float>(img.size());
    std::vector<cv::Point2f> hull;
    cv::convexHull(img, hull);
    const double size = std::sqrt(cv::contourArea(hull) / (w * h));
    double tiltX = 0, tiltY = 0;
    const cv::Mat H = cv::findHomography(plane, img, 0);
    if (!H.empty()) {
      const cv::Matx33d M = roughK.inv() * cv::Matx33d(H);
      const cv::Vec3d r1(M(0, 0), M(1, 0), M(2, 0)), r2(M(0, 1), M(1, 1), M(2, 1));
      cv::Vec3d n = cv::normalize(r1).cross(cv::normalize(r2));
      if (n[2] < 0) n = -n;
      tiltX = std::atan2(n[0], n[2]);
      tiltY = std::atan2(n[1], n[2]);
    }
    descriptors.push_back({centre.x / w, centre.y / h, size, tiltX, tiltY});
  }
  std::vector<std::size_t> chosen;
  std::vector<double> distance(views_.size(), std::numeric_limits<double>::infinity());
  std::size_t next = 0;  // start with the largest board: the best-conditioned single view
  for (std::size_t i = 1; i < views_.size(); ++i)
    if (descriptors[i][2] > descriptors[next][2]) next = i;
  while (static_cast<int>(chosen.size()) < params_.maxViews) {
    chosen.push_back(next);
    distance[next] = -1.0;
    for (std::size_t i = 0; i < views_.size(); ++i)
      if (distance[i] >= 0.0)
        distance[i] = std::min(distance[i], cv::norm(descriptors[i] - descriptors[next]));
    next = static_cast<std::size_t>(std::max_element(distance.begin(), distance.end()) -
                                    distance.begin());
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

CalibrationResult CameraCalibrator::calibrate() const {
  if (views_.empty())
    throw Error("the board (" + detector_.board().toString() + ") was found in none of the " +
                std::to_string(examined_) + " images");
  if (static_cast<int>(views_.size()) < params_.minViews)
    throw Error("the board was found in only " + std::to_string(views_.size()) + " of " +
                std::to_string(examined_) + " images; at least " +
                std::to_string(params_.minViews) + " views are needed");
  const std::vector<std::size_t> used = selectSpreadViews();
  std::vector<std::vector<cv::Point3f>> objectPoints;
  std::vector<std::vector<cv::Point2f>> imagePoints;
  for (std::size_t i : used) {
    objectPoints.push_back(views_[i].observation.objectPoints);
    imagePoints.push_back(views_[i].observation.imagePoints);
  }
  int flags = 0;
  cv::Mat K = cv::Mat::eye(3, 3, CV_64F), dist;
  if (params_.fixAspectRatio) flags |= cv::CALIB_FIX_ASPECT_RATIO;
  if (params_.zeroTangent) flags |= cv::CALIB_ZERO_TANGENT_DIST;
  if (params_.fixK3) flags |= cv::CALIB_FIX_K3;
  std::vector<cv::Mat> rvecs, tvecs;
  double rms = 0.0;
  try {
    rms = cv::calibrateCamera(
        objectPoints, imagePoints, imageSize_, K, dist, rvecs, tvecs, flags,
        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-12));
  } catch (const cv::Exception& e) {
    throw Error("cv::calibrateCamera failed: " + e.err);
  }
  if (!std::isfinite(rms) || !cv::checkRange(K) || !cv::checkRange(dist))
    throw Error("calibration diverged (non-finite result); add views with more varied tilt");

  CalibrationResult result;
  Eigen::Matrix3d Ke;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) Ke(r, c) = K.at<double>(r, c);
  std::vector<double> d(dist.ptr<double>(), dist.ptr<double>() + dist.total());
  result.camera = PinholeCamera(Ke, imageSize_, d);
  try {
    result.camera.check();
  } catch (const Error& e) {
    throw Error(std::string("calibration produced an invalid camera: ") + e.what());
  }
  result.rmsPx = rms;
  for (std::size_t k = 0; k < used.size(); ++k) {
    std::vector<cv::Point2f> projected;
    cv::projectPoints(objectPoints[k], rvecs[k], tvecs[k], K, dist, projected);
    const double err = cv::norm(imagePoints[k], projected, cv::NORM_L2);
    result.views.push_back({views_[used[k]].label, static_cast<int>(projected.size()),
                            err / std::sqrt(static_cast<double>(projected.size()))});
  }
  result.rejected = rejected_;
  result.imagesExamined = examined_;
  result.viewsFound = views_.size();
  return result;
}

}  // namespace reftrack
