#pragma once
// WideBaselineMatcher (paper Sec. 6.2, SPEC §4): matches the corners of the current frame V_k to a
// reference image far away in viewpoint. The frame-to-frame homography H (V_k -> V_{k-1}) and
// the local affine L (V_{k-1} -> reference) of the 3 nearest previous matches chain into
// W = L H (Eq. 18), and candidates are scored with the warped correlation of Eq. 19.
// Computed from the reference side, so each warped window is sampled once: for every reference
// corner p_A, L comes from the previous matches nearest p_A, its predicted frame position is
// p'_k = W^-1 p_A, the reference around p_A is sampled through O W once, and each frame corner
// inside the (2dx+1) x (2dy+1) window around p'_k scores as the dot product of that window with
// its own precomputed one (MatchableFrame). The best candidate above the threshold is kept; each
// frame corner and each reference corner is used at most once. With a cap on the reference
// corners (WideBaselineParams), corners are taken in MatchableReference::order and those
// predicted outside the frame do not count.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "engine/config/WideBaselineParams.hpp"
#include "engine/features/CornerGrid.hpp"

namespace reftrack {

// A reference image ready for matching: 8-bit grey pixels, its corners with a lookup grid, and
// the order in which corners are tried: the `preferred` ones (e.g. those with a 3D point) first,
// each group interleaved over an 8x6 grid so that any prefix is spread over the image.
struct MatchableReference {
  cv::Mat gray8;  // CV_8UC1
  std::vector<cv::Point2f> corners;
  CornerGrid grid;
  std::vector<int> order;
  static MatchableReference build(const cv::Mat& image, std::vector<cv::Point2f> corners,
                                  const std::vector<char>& preferred = {});
};

// The current frame ready for matching to both references: its corners on a lookup grid and the
// (2n+1)^2 window around each, sampled once (sampleFrameWindow) and shared by V_A and V_B.
struct MatchableFrame {
  cv::Size size;
  std::vector<cv::Point2f> corners;
  CornerGrid grid;
  int halfWindow = 0;
  std::vector<float> windows;  // (2n+1)^2 floats per corner
  std::vector<char> valid;     // the window is inside the frame and textured
  // gray8: CV_8UC1 (a BGR frame is converted).
  static MatchableFrame build(const cv::Mat& gray8, std::vector<cv::Point2f> corners,
                              int halfWindow);
  const float* window(int corner) const {
    const int side = 2 * halfWindow + 1;
    return windows.data() +
           static_cast<std::size_t>(corner) * static_cast<std::size_t>(side * side);
  }
};

// A previous-frame corner and the reference corner it was matched to.
struct PreviousMatch {
  cv::Point2f previous;
  int referenceCorner = -1;
};

struct WideBaselineMatch {
  int frameCorner = -1, referenceCorner = -1;
  double score = 0.0;
  cv::Point2d predicted;  // p'_k = W^-1 p_A: where the reference corner was expected in V_k
  // The local linear map of W at the frame corner (frame offsets -> reference offsets), for the
  // frame-side alignment of the reference window; none when the match was not made through W.
  std::optional<cv::Matx22d> frameToReference{};
};

// The local affine maps reference -> previous frame (L^-1 of Eq. 18) at the first corners of
// MatchableReference::order (none where the nearest previous matches are degenerate).
struct MapsToPrevious {
  std::vector<std::optional<cv::Matx33d>> atOrder;
};

class WideBaselineMatcher {
 public:
  explicit WideBaselineMatcher(WideBaselineParams params) : params_(params) {}
  void setParams(const WideBaselineParams& params) { params_ = params; }

  // H_kToPrev maps current-frame pixels to the previous frame. dx, dy are given at 320x240 and
  // scale with the image size (ResolutionScale.hpp). The frame's half window must be params.n.
  // `computed`: mapsToPrevious() of the same previous matches and reference, when it was
  // computed beforehand (the same matches either way).
  std::vector<WideBaselineMatch> match(const MatchableFrame& frame, const cv::Matx33d& H_kToPrev,
                                       const std::vector<PreviousMatch>& previous,
                                       const MatchableReference& reference,
                                       const MapsToPrevious* computed = nullptr) const;

  // The part of match() that does not depend on H, for the first `count` corners of the
  // reference's order: it can run while H is being estimated.
  MapsToPrevious mapsToPrevious(const std::vector<PreviousMatch>& previous,
                                const MatchableReference& reference, std::size_t count) const;

  // The local affine map (previous frame -> reference) at `p` from the nearest previous matches,
  // as a 3x3 matrix; false when the neighbours are degenerate (collinear) or too few.
  bool localAffine(cv::Point2d p, const std::vector<PreviousMatch>& previous,
                   const MatchableReference& reference, cv::Matx33d& L) const;

 private:
  WideBaselineParams params_;
};

}  // namespace reftrack
