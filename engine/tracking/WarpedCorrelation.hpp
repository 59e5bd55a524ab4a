#pragma once
// WarpedCorrelation (paper Eq. 19, SPEC §4): NCC between the (2n+1)^2 window of the current frame
// around a corner p_k and the reference image sampled, bilinearly, at O W m for every window pixel
// m — W maps the current frame to the reference (W = L H) and O shifts the warped window so it is
// centred on a candidate corner p_A. Unlike plain NCC, the score survives the rotation, scale and
// shear between views that are far apart.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

class WarpedCorrelation {
 public:
  // frame, reference: CV_32FC1 grey images (0..255).
  WarpedCorrelation(const cv::Mat& frame, const cv::Mat& reference, int halfWindow);

  // The frame window around pK, zero-mean and unit-norm; empty when the window leaves the frame
  // or is textureless (then no score is defined).
  struct FramePatch {
    std::vector<float> values;
    cv::Point2d centre;
    bool valid() const { return !values.empty(); }
  };
  FramePatch framePatch(cv::Point2f pK) const;

  // Eq. 19 score in [-1, 1] of `patch` against the reference sampled at
  // W(m) - W(pK) + pA; returns -1 when the warped window leaves the reference or is flat.
  double score(const FramePatch& patch, const cv::Matx33d& W, cv::Point2d pA) const;

  int halfWindow() const { return n_; }

 private:
  cv::Mat frame_, reference_;
  int n_;
};

// The precomputed form for many candidates (WideBaselineMatcher): each window is sampled once as
// a zero-mean, unit-norm vector of (2n+1)^2 floats, and a pair's Eq. 19 score is the dot product
// of the two vectors. Both windows are centred exactly on their sub-pixel corners. The samplers
// return false (leaving `out` unspecified) when the window leaves the image or is flat.
// The frame window around the sub-pixel pK, bilinear (gray8: CV_8UC1).
bool sampleFrameWindow(const cv::Mat& gray8, cv::Point2d pK, int n, float* out);
// The reference (CV_8UC1 or CV_32FC1: the same samples for the same pixel values) sampled at
// pA + W(pK + m) - W(pK) for every window offset m, with W mapping frame pixels to reference pixels
// (O W of Eq. 19 with O centring the window on pA); W is taken to first order at pK (its Jacobian:
// exact for an affine W, within a few thousandths of a pixel for tracking's W = L H over a window).
bool sampleWarpedReferenceWindow(const cv::Mat& reference, const cv::Matx33d& W, cv::Point2d pK,
                                 cv::Point2d pA, int n, float* out);
// A hint, no effect on results: starts loading the reference pixels that the same call of
// sampleWarpedReferenceWindow will read (8-bit reference; nothing for other types), so that a
// caller can fetch the next window while it scores the current one.
void prefetchWarpedReferenceWindow(const cv::Mat& reference, const cv::Matx33d& W, cv::Point2d pK,
                                   cv::Point2d pA, int n);
// Dot product of two sampled windows of `count` floats: their Eq. 19 score in [-1, 1].
float windowScore(const float* a, const float* b, int count);

}  // namespace reftrack
