#pragma once
// OrbHomographyBaseline: what users reach for today to register a frame to a reference image —
// OpenCV ORB (1000 features), brute-force Hamming matching with cross-check, and
// cv::findHomography RANSAC (3 px at 640x480, scaled with the image) against the reference. The
// benchmark runs it on the very frames the HomographyTracker sees.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <vector>

namespace reftrack::app {

struct OrbHomographyResult {
  bool tracked = false;
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> frame
  int matches = 0;
  int inliers = 0;
};

class OrbHomographyBaseline {
 public:
  // reference: 8-bit grey or BGR. Throws reftrack::Error when it is empty or has < 8 features.
  explicit OrbHomographyBaseline(const cv::Mat& reference, int features = 1000);

  // A frame fails with fewer than 8 inliers or under 35% inliers among the cross-checked matches
  // (the tracker's own failure rule), or a near-singular H.
  OrbHomographyResult track(const cv::Mat& frame) const;

 private:
  cv::Ptr<cv::ORB> orb_;
  cv::BFMatcher matcher_;
  cv::Size size_;
  std::vector<cv::KeyPoint> refKeypoints_;
  cv::Mat refDescriptors_;
};

}  // namespace reftrack::app
