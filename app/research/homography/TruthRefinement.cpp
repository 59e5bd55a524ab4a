#include "app/research/homography/TruthRefinement.hpp"

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>

#include "app/research/homography/HomographyGroundTruth.hpp"

namespace reftrack::app {

RefinedTruth refineTruthByEcc(const cv::Mat& reference, const cv::Mat& frame,
                              const cv::Matx33d& givenH) {
  RefinedTruth out;
  out.H = givenH;
  if (reference.empty() || frame.empty()) return out;
  // findTransformECC(template, input, warp): warp maps template (reference) pixels to input
  // (frame) pixels, as H does. Gaussian pre-filtering (5x5) widens its basin for a start several
  // pixels off.
  cv::Mat warp(cv::Matx33f(givenH * (1.0 / givenH(2, 2))));
  try {
    out.correlation = cv::findTransformECC(
        reference, frame, warp, cv::MOTION_HOMOGRAPHY,
        cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 300, 1e-7), cv::noArray(),
        5);
  } catch (const cv::Exception&) {
    return out;  // ECC diverged or the images do not overlap
  }
  cv::Mat w64;
  warp.convertTo(w64, CV_64F);
  cv::Matx33d H(w64);
  H *= 1.0 / H(2, 2);
  if (!std::isfinite(cv::norm(H))) return out;
  out.converged = true;
  out.H = H;
  out.movedPx = referenceCornerError(H, givenH, reference.size());
  return out;
}

}  // namespace reftrack::app
