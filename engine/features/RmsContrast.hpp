#pragma once
// RMS contrast: the standard deviation of the grey levels in the (window x window) square
// centred on a point (rounded to the nearest pixel), clipped to the image. Paper Fig. 7 relates
// it to a corner's positional accuracy.
#include <opencv2/core.hpp>

namespace reftrack {

// gray: CV_8UC1. Throws reftrack::Error on an empty/other-type image or an even window.
double rmsContrast(const cv::Mat& gray, cv::Point2f centre, int window);

}  // namespace reftrack
