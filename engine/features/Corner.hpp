#pragma once
// Corner: one detected image corner — sub-pixel position (OpenCV pixel-centre convention),
// Harris response, and the RMS contrast (grey-level standard deviation) of the square window
// around it, from which the corner's positional variance follows (paper Fig. 7).
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack {

struct Corner {
  cv::Point2f position;
  float response = 0.0f;
  float contrast = 0.0f;
};

std::vector<cv::Point2f> positionsOf(const std::vector<Corner>& corners);

}  // namespace reftrack
