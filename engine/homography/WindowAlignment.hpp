#pragma once
// WindowAlignment: Lucas-Kanade alignment of a reference, seen through a homography, to a frame
// at a set of points — sampling only the points' windows. For each point q = H p the template is
// the reference warped by H over the (2 half + 1)^2 window around q (bilinear, through H^-1, with
// a one-pixel border for its gradient); the translation d that makes the frame around q + d match
// it is found by Lucas-Kanade with the template's gradients (the inverse-compositional form
// cv::calcOpticalFlowPyrLK uses on one level). Warping and differentiating the whole image
// (cv::warpPerspective + the LK pyramid) costs far more than the windows when the points cover a
// fraction of it (measured: HomographyRefiner, bench-homography).
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

struct WindowAlignmentResult {
  std::vector<cv::Point2f> found;  // q + d per point (frame pixels)
  std::vector<uchar> status;       // 1: converged inside the frame with a textured template
};

// reference, frame: CV_8UC1; H: reference -> frame; predicted[i] = H referencePoints[i] (the
// caller's transfer, kept to avoid a second one). half >= 1. A point fails (status 0) when its
// template leaves the reference, is flat (smaller eigenvalue of the gradient matrix below 1e-2
// grey levels^2 per pixel), its frame window leaves the frame, or it drifts by more than `half`.
WindowAlignmentResult alignWindows(const cv::Mat& reference, const cv::Mat& frame,
                                   const cv::Matx33d& H, const std::vector<cv::Point2f>& predicted,
                                   int half, int maxIterations = 20, double epsilonPx = 0.01);

}  // namespace reftrack
