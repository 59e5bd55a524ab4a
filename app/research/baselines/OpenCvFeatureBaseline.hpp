#pragma once
// OpenCvFeatureBaseline: the plain OpenCV recipe for registering an image to a reference —
// SIFT, AKAZE or ORB keypoints with default settings, brute-force k = 2 matching with Lowe's
// ratio test (0.75), and cv::findHomography RANSAC (3 px at 640x480, scaled with the image).
// The comparison the pairs experiment runs the tracker against.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

namespace reftrack::app {

struct FeatureBaselineResult {
  bool found = false;  // a homography with >= 8 RANSAC inliers and a sane determinant
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> frame
  int matches = 0, inliers = 0;
};

class OpenCvFeatureBaseline {
 public:
  // detector: "sift", "akaze" or "orb" (ORB with 1000 features); reference: 8-bit grey or BGR.
  // Throws reftrack::Error on another name, an empty reference, or < 8 reference keypoints.
  OpenCvFeatureBaseline(const std::string& detector, const cv::Mat& reference);

  FeatureBaselineResult registerFrame(const cv::Mat& frame) const;  // frame: any size

  const std::string& name() const { return name_; }

 private:
  std::string name_;
  cv::Ptr<cv::Feature2D> detector_;
  cv::Ptr<cv::BFMatcher> matcher_;
  std::vector<cv::KeyPoint> refKeypoints_;
  cv::Mat refDescriptors_;
};

}  // namespace reftrack::app
