#include "app/research/baselines/OrbHomographyBaseline.hpp"

#include <cmath>
#include <opencv2/calib3d.hpp>

#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/CornerDetector.hpp"

namespace reftrack::app {

namespace {

constexpr int kMinInliers = 8;
constexpr double kMinInlierRatio = 0.35;
constexpr double kRansacPxAt640x480 = 3.0;  // OpenCV's documented default threshold

}  // namespace

OrbHomographyBaseline::OrbHomographyBaseline(const cv::Mat& reference, int features)
    : orb_(cv::ORB::create(features)), matcher_(cv::NORM_HAMMING, /*crossCheck=*/true) {
  if (reference.empty()) throw Error("ORB baseline: the reference image is empty");
  const cv::Mat gray = toGray8(reference);
  size_ = gray.size();
  orb_->detectAndCompute(gray, cv::noArray(), refKeypoints_, refDescriptors_);
  if (refKeypoints_.size() < static_cast<size_t>(kMinInliers))
    throw Error("ORB baseline: only " + std::to_string(refKeypoints_.size()) +
                " ORB features in the reference image");
}

OrbHomographyResult OrbHomographyBaseline::track(const cv::Mat& frame) const {
  OrbHomographyResult out;
  const cv::Mat gray = toGray8(frame);
  if (gray.size() != size_) throw Error("ORB baseline: frame size differs from the reference");
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb_->detectAndCompute(gray, cv::noArray(), keypoints, descriptors);
  if (descriptors.empty()) return out;
  std::vector<cv::DMatch> matches;
  matcher_.match(refDescriptors_, descriptors, matches);
  out.matches = static_cast<int>(matches.size());
  if (out.matches < kMinInliers) return out;
  std::vector<cv::Point2f> src, dst;
  for (const cv::DMatch& m : matches) {
    src.push_back(refKeypoints_[static_cast<size_t>(m.queryIdx)].pt);
    dst.push_back(keypoints[static_cast<size_t>(m.trainIdx)].pt);
  }
  std::vector<uchar> mask;
  const double threshold =
      kRansacPxAt640x480 * resolutionScale(size_) / resolutionScale(cv::Size(640, 480));
  const cv::Mat H = cv::findHomography(src, dst, cv::RANSAC, threshold, mask);
  if (H.empty()) return out;
  out.H = cv::Matx33d(H);
  for (uchar m : mask) out.inliers += m ? 1 : 0;
  const double det = cv::determinant(out.H * (1.0 / out.H(2, 2)));
  out.tracked = out.inliers >= kMinInliers && out.inliers >= kMinInlierRatio * out.matches &&
                std::isfinite(det) && std::abs(det) > 0.05 && std::abs(det) < 20.0;
  return out;
}

}  // namespace reftrack::app
