#pragma once
// KeypointFeatures: the viewpoint-invariant keypoints of the relocalisation layer (issue 13) —
// one detector + descriptor by name (orb | akaze | sift, OpenCV features2d), a cap on the number
// kept (the strongest), and descriptor matching with Lowe's ratio test and a mutual check.
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>
#include <vector>

namespace reftrack {

class KeypointFeatures {
 public:
  // Throws reftrack::Error for an unknown kind (the accepted names are listed).
  explicit KeypointFeatures(const std::string& kind);

  const std::string& kind() const { return kind_; }
  int normType() const;  // cv::NORM_HAMMING (orb, akaze) or cv::NORM_L2 (sift)

  // Detects and describes at most `maxKeypoints` keypoints (the strongest) of an 8-bit grey or
  // BGR image. Descriptors: one row per keypoint. ORB only: `finerLevels` pyramid levels above
  // the image (magnified by 1.2 per level, for views closer than the image's) and
  // `coarserLevels` beyond ORB's usual 8 (for farther views). `scale` < 1: detected on the image
  // reduced by that factor (cv::INTER_AREA); keypoints always in the image's own pixels.
  void detectAndDescribe(const cv::Mat& image, int maxKeypoints,
                         std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
                         int finerLevels = 0, int coarserLevels = 0, double scale = 1.0) const;

 private:
  std::string kind_;
};

// For each query row, its nearest train row when it passes the ratio test (nearest < ratio *
// second nearest); with `mutual`, also only when that train row's nearest query row (under the
// same ratio test) is the query row itself. queryIdx/trainIdx index the two descriptor sets.
std::vector<cv::DMatch> matchDescriptors(const cv::Mat& query, const cv::Mat& train, int normType,
                                         double ratio, bool mutual);

// All distances of query rows (matrix rows) to train rows (columns), CV_32F: cv::batchDistance's
// result, with the CPU's popcount for Hamming (this OpenCV's Hamming has none).
cv::Mat descriptorDistances(const cv::Mat& query, const cv::Mat& train, int normType);

// The distance of row `rowA` of descriptors `a` to row `rowB` of `b` (same type and length) under
// normType: what cv::norm gives, with the CPU's popcount for Hamming.
float descriptorDistance(const cv::Mat& a, int rowA, const cv::Mat& b, int rowB, int normType);

}  // namespace reftrack
