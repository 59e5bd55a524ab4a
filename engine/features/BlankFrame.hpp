#pragma once
// BlankFrame: whether a frame shows nothing to search (a covered lens, a black or uniform frame):
// the means of its 8x8-pixel cells vary by less than `maxStdDev` (standard deviation, 8-bit
// levels). Cheap next to any detection, so a lost tracker can skip such frames.
#include <opencv2/core.hpp>

namespace reftrack {

// 8-bit BGR or grey; an empty frame is blank.
bool isBlankFrame(const cv::Mat& frame, double maxStdDev = 2.0);

}  // namespace reftrack
