#pragma once
// RobustHomographyEstimator (paper Sec. 3.2, 7.3; SPEC §2, §5): RANSAC over minimal 4-point
// solutions with the paper's heuristics (at most 70 iterations; accept at once
// with > 75% support after >= 15 iterations; the 4 sampled points pairwise >= 60 px apart at
// 320x240, once more at half that spacing when the pass would fail; near-singular H rejected by
// a determinant test), then DLT on all inliers and a
// Levenberg-Marquardt refinement of the Euclidean transfer error on the inliers.
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "engine/config/RansacParams.hpp"

namespace reftrack {

struct HomographyEstimate {
  bool success = false;
  cv::Matx33d H = cv::Matx33d::eye();  // src -> dst, h33 = 1
  std::vector<char> inliers;           // one flag per correspondence
  int inlierCount = 0;
  double inlierRatio = 0.0;       // inliers / correspondences
  int iterations = 0;             // RANSAC iterations run (both passes)
  double rmsTransferError = 0.0;  // over the inliers (pixels)
  std::string failure;            // why success is false
};

class RobustHomographyEstimator {
 public:
  explicit RobustHomographyEstimator(RansacParams params = {});  // throws on bad params

  // src/dst: matched points (same length); imageSize: of the src image (scales the spacing);
  // dstSize: of the dst image (scales the inlier threshold; empty: imageSize).
  // quality: optional, one value per match (higher = more likely correct, e.g. the NCC score);
  // with progressive_sampling the samples are drawn from the best-ranked matches first.
  // Fails (success = false, with a reason) below min_inlier_ratio or min_inliers. Throws
  // reftrack::Error when the lists differ in length.
  HomographyEstimate estimate(const std::vector<cv::Point2f>& src,
                              const std::vector<cv::Point2f>& dst, cv::Size imageSize,
                              const std::vector<float>& quality = {}, cv::Size dstSize = {}) const;

  // Finite and |det(H / h33)| within [min_determinant, 1 / min_determinant].
  bool acceptable(const cv::Matx33d& H) const;

  const RansacParams& params() const { return params_; }

 private:
  RansacParams params_;
};

// Fills `out` from H and its inlier indices (flags, count, ratio over all matches, RMS transfer
// error) and applies the params' inlier rules: success, or the failure naming the rule broken.
void summariseEstimate(HomographyEstimate& out, const cv::Matx33d& H,
                       const std::vector<int>& inliers, const std::vector<cv::Point2f>& src,
                       const std::vector<cv::Point2f>& dst, const RansacParams& params);

// Minimises sum w_i |H src_i - dst_i|^2 over the 8 free entries of H (Levenberg-Marquardt with
// the analytic Jacobian, in normalised coordinates) for i in indices; weights: one per index
// (all 1 when empty). Returns the refined H (h33 = 1), or H unchanged when the solve fails.
cv::Matx33d refineHomography(const cv::Matx33d& H, const std::vector<cv::Point2f>& src,
                             const std::vector<cv::Point2f>& dst, const std::vector<int>& indices,
                             const std::vector<double>& weights = {});

}  // namespace reftrack
