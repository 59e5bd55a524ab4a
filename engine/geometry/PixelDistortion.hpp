#pragma once
// distortPixels: ideal (undistorted) pixel coordinates of a camera to the pixels its lens records
// them at — the inverse of PinholeCamera::undistortPixels, as cv::projectPoints of the ray K^-1 p.
#include <opencv2/core.hpp>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack {

// The pixels unchanged when the camera has no distortion.
std::vector<cv::Point2f> distortPixels(const PinholeCamera& camera,
                                       const std::vector<cv::Point2f>& idealPixels);

}  // namespace reftrack
