#pragma once
// A check of a data set's homography: OpenCV's ECC alignment (Evangelidis & Psarakis 2008,
// cv::findTransformECC, an implementation independent of the tracker's) of the reference warped
// by the given H to the frame, started from that H. Where the given H is exact, ECC leaves it
// (Oxford ubc 1->3: 0.015 px at the reference's corners); where it moves it by pixels, and the
// feature-based peers agree with where it ends, the given H is what is off.
#include <opencv2/core.hpp>

namespace reftrack::app {

struct RefinedTruth {
  bool converged = false;
  cv::Matx33d H = cv::Matx33d::eye();  // reference -> frame; the given H when !converged
  double movedPx = 0.0;                // mean distance at the reference's corners from the given H
  double correlation = 0.0;            // ECC's final correlation coefficient (1: identical)
};

// reference, frame: 8-bit grey; givenH: reference -> frame. Never throws on a pair ECC cannot
// align (converged = false).
RefinedTruth refineTruthByEcc(const cv::Mat& reference, const cv::Mat& frame,
                              const cv::Matx33d& givenH);

}  // namespace reftrack::app
