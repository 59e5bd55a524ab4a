#pragma once
// WideBaselineMatcher (paper Sec. 6.2, SPEC §4): matches the corners of the current frame V_k to a
// reference image far away in viewpoint. For a corner p_k the frame-to-frame homography H
// (V_k -> V_{k-1}) predicts p'_{k-1} = H p_k; the local affine L of the 3 nearest previous-frame
// corners that had reference matches maps it on, p'_A = L H p_k = W p_k (Eq. 18); reference
// corners inside the (2dx+1) x (2dy+1) window around p'_A are scored with the warped correlation
// of Eq. 19 and the best one above the threshold is kept (each reference corner at most once).
#include <opencv2/core.hpp>
#include <vector>

#include "engine/config/WideBaselineParams.hpp"
#include "engine/tracking/CornerGrid.hpp"

namespace reftrack {

// A reference image ready for matching: grey float pixels and its corners with a lookup grid.
struct MatchableReference {
  cv::Mat imageF;  // CV_32FC1
  std::vector<cv::Point2f> corners;
  CornerGrid grid;
  static MatchableReference build(const cv::Mat& image, std::vector<cv::Point2f> corners);
};

// A previous-frame corner and the reference corner it was matched to.
struct PreviousMatch {
  cv::Point2f previous;
  int referenceCorner = -1;
};

struct WideBaselineMatch {
  int frameCorner = -1, referenceCorner = -1;
  double score = 0.0;
  cv::Point2d predicted;  // p'_A = W p_k
};

class WideBaselineMatcher {
 public:
  explicit WideBaselineMatcher(WideBaselineParams params) : params_(params) {}
  void setParams(const WideBaselineParams& params) { params_ = params; }

  // frameF: CV_32FC1 current frame; H_kToPrev maps current-frame pixels to the previous frame.
  // dx, dy are given at 320x240 and scale with the image size (ResolutionScale.hpp).
  std::vector<WideBaselineMatch> match(const cv::Mat& frameF,
                                       const std::vector<cv::Point2f>& frameCorners,
                                       const cv::Matx33d& H_kToPrev,
                                       const std::vector<PreviousMatch>& previous,
                                       const MatchableReference& reference) const;

  // The local affine map (previous frame -> reference) at `p` from the nearest previous matches,
  // as a 3x3 matrix; false when the neighbours are degenerate (collinear) or too few.
  bool localAffine(cv::Point2d p, const std::vector<PreviousMatch>& previous,
                   const MatchableReference& reference, cv::Matx33d& L) const;

 private:
  // localAffine restricted to the previous matches listed in `nearby`.
  bool localAffineFrom(cv::Point2d p, const std::vector<PreviousMatch>& previous,
                       const std::vector<int>& nearby, const MatchableReference& reference,
                       cv::Matx33d& L) const;
  WideBaselineParams params_;
};

}  // namespace reftrack
