#include "app/research/baselines/OpenCvFeatureBaseline.hpp"

#include <cmath>
#include <opencv2/calib3d.hpp>

#include "app/research/baselines/OpenCvFeatures.hpp"
#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack::app {

namespace {

constexpr int kMinInliers = 8;
constexpr float kRatio = 0.75f;             // Lowe (2004)
constexpr double kRansacPxAt640x480 = 3.0;  // OpenCV's documented default threshold

}  // namespace

OpenCvFeatureBaseline::OpenCvFeatureBaseline(const std::string& detector, const cv::Mat& reference)
    : name_(detector) {
  const OpenCvFeatures features = openCvFeatures(detector, 1000);
  detector_ = features.detector;
  matcher_ = cv::BFMatcher::create(features.norm);
  if (reference.empty()) throw Error("feature baseline: the reference image is empty");
  detector_->detectAndCompute(toGray8(reference), cv::noArray(), refKeypoints_, refDescriptors_);
  if (refKeypoints_.size() < static_cast<size_t>(kMinInliers))
    throw Error("feature baseline: only " + std::to_string(refKeypoints_.size()) + " " + name_ +
                " keypoints in the reference image");
}

FeatureBaselineResult OpenCvFeatureBaseline::registerFrame(const cv::Mat& frame) const {
  FeatureBaselineResult out;
  if (frame.empty()) throw Error("feature baseline: the frame is empty");
  const cv::Mat gray = toGray8(frame);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  detector_->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  if (keypoints.size() < 2) return out;
  std::vector<std::vector<cv::DMatch>> knn;
  matcher_->knnMatch(refDescriptors_, descriptors, knn, 2);
  std::vector<cv::Point2f> src, dst;
  for (const auto& m : knn)
    if (m.size() == 2 && m[0].distance < kRatio * m[1].distance) {
      src.push_back(refKeypoints_[static_cast<size_t>(m[0].queryIdx)].pt);
      dst.push_back(keypoints[static_cast<size_t>(m[0].trainIdx)].pt);
    }
  out.matches = static_cast<int>(src.size());
  if (out.matches < kMinInliers) return out;
  std::vector<uchar> mask;
  const double threshold =
      kRansacPxAt640x480 * resolutionScale(gray.size()) / resolutionScale(cv::Size(640, 480));
  const cv::Mat H = cv::findHomography(src, dst, cv::RANSAC, threshold, mask);
  if (H.empty()) return out;
  out.H = cv::Matx33d(H) * (1.0 / H.at<double>(2, 2));
  for (uchar m : mask) out.inliers += m ? 1 : 0;
  const double det = cv::determinant(out.H);
  out.found = out.inliers >= kMinInliers && std::isfinite(det) && std::abs(det) > 1e-3 &&
              std::abs(det) < 1e3;
  return out;
}

}  // namespace reftrack::app
