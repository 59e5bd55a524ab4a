#pragma once
// Sub-pixel corner refinement (Foerstner's operator, the model behind cv::cornerSubPix): the
// corner q is the point every image gradient g_i in the window points away from,
// sum_i w_i g_i g_i^T (q - p_i) = 0, solved in closed form (2x2). Gradients are central
// differences on the integer pixel grid of a window centred on the rounded estimate (no
// resampling), Gaussian-weighted as cv::cornerSubPix weights them; the window is re-centred until
// the rounded estimate stops moving.
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

// gray: CV_8UC1. halfWindow >= 1: windows of (2 halfWindow + 1)^2 pixels. A point whose window
// leaves the image, whose window has no two-directional gradient, or whose estimate wanders
// further than halfWindow from where it started keeps its position. Throws reftrack::Error on
// an empty/other-type image or halfWindow < 1.
void refineCornersSubPixel(const cv::Mat& gray, std::vector<cv::Point2f>& points, int halfWindow);

}  // namespace reftrack
