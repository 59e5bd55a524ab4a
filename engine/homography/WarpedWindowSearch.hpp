#pragma once
// WarpedWindowSearch: guided correlation without frame corners — each reference window, warped
// into the frame's geometry by a predicted homography (Eq. 19), is correlated (NCC) at every
// pixel within +-radius of its predicted position; the best position, refined to sub-pixel by a
// parabola through the peak and its neighbours, is its match when the NCC reaches minScore and
// the peak lies strictly inside the search square. Cold registration uses it where a frame's
// Harris corners do not repeat the reference's (a strong change of scale or viewpoint).
#include <opencv2/core.hpp>
#include <vector>

#include "engine/matching/NccCorrelation.hpp"

namespace reftrack {

struct WindowMatch {
  int reference = 0;     // index into the reference points / windows
  cv::Point2f position;  // in the frame (pixels, sub-pixel)
  float score = 0.0f;    // NCC at the integer peak
};

// frameGray: CV_8UC1; windows: the reference windows warped into the frame's geometry (invalid
// ones are skipped); predicted: one position per window. Throws reftrack::Error when the sizes
// differ, radius < 1 or the frame is not 8-bit grey.
std::vector<WindowMatch> searchWarpedWindows(const cv::Mat& frameGray, const NccPatches& windows,
                                             const std::vector<cv::Point2f>& predicted, int radius,
                                             double minScore);

}  // namespace reftrack
