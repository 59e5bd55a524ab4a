#include "app/tracking/NonPlanarAdvice.hpp"

#include <opencv2/imgproc.hpp>

namespace reftrack::app {

std::optional<double> NonPlanarAdvice::supportShare(const HomographyTrackResult& result,
                                                    cv::Size referenceSize, cv::Size frameSize) {
  if (!result.tracked || referenceSize.empty() || frameSize.empty()) return std::nullopt;
  const cv::Matx33d Hinv = result.H.inv();
  std::vector<cv::Point2f> frameRect{
      {0.f, 0.f},
      {static_cast<float>(frameSize.width), 0.f},
      {static_cast<float>(frameSize.width), static_cast<float>(frameSize.height)},
      {0.f, static_cast<float>(frameSize.height)}};
  std::vector<cv::Point2f> back;
  for (const cv::Point2f& p : frameRect) {
    const cv::Vec3d q = Hinv * cv::Vec3d(p.x, p.y, 1.0);
    if (!(q[2] > 1e-9)) return std::nullopt;  // the frame's corner maps behind: no clean overlap
    back.emplace_back(static_cast<float>(q[0] / q[2]), static_cast<float>(q[1] / q[2]));
  }
  std::vector<cv::Point2f> refRect{
      {0.f, 0.f},
      {static_cast<float>(referenceSize.width), 0.f},
      {static_cast<float>(referenceSize.width), static_cast<float>(referenceSize.height)},
      {0.f, static_cast<float>(referenceSize.height)}};
  std::vector<cv::Point2f> backHull, overlap;
  cv::convexHull(back, backHull);
  const double overlapArea = cv::intersectConvexConvex(refRect, backHull, overlap);
  if (!(overlapArea > 0)) return std::nullopt;
  std::vector<cv::Point2f> inliers;
  for (const auto& m : result.inlierMatches) inliers.push_back(m.first);
  if (inliers.size() < 3) return 0.0;
  std::vector<cv::Point2f> hull;
  cv::convexHull(inliers, hull);
  return std::min(1.0, cv::contourArea(hull) / overlapArea);
}

void NonPlanarAdvice::add(const HomographyTrackResult& result, cv::Size referenceSize,
                          cv::Size frameSize) {
  const std::optional<double> share = supportShare(result, referenceSize, frameSize);
  recent_.push_back({!result.tracked,
                     !result.tracked && result.failure.find("refused by the registration check") !=
                                            std::string::npos,
                     share && *share < kMinSupportShare});
  if (static_cast<int>(recent_.size()) > kWindow) recent_.pop_front();
  if (advice()) everShown_ = true;
}

std::optional<std::string> NonPlanarAdvice::advice() const {
  int lost = 0, refused = 0, partial = 0;
  for (const Outcome& o : recent_) {
    lost += o.lost ? 1 : 0;
    refused += o.refused ? 1 : 0;
    partial += o.partial ? 1 : 0;
  }
  if ((lost < kMinLost || refused < kMinRefused) && partial < kMinPartial) return std::nullopt;
  return message();
}

const char* NonPlanarAdvice::message() {
  return "homography mode follows one flat surface: this view does not fit one homography (a 3-D "
         "object, or things moving in front of the target), or only a small part of the "
         "reference follows it. Use a reference image cropped to one "
         "flat face of the object, or build a map of it (reftrack prepare) and track in 6-DOF "
         "mode.";
}

}  // namespace reftrack::app
