#pragma once
// Homographies through a distorting lens. A plane (or a rotating camera) seen through a lens is
// not a homography between the recorded images, only between their undistorted versions
// (FrameUndistorter, same K); a point of the recorded reference image reaches the recorded frame
// by undistorting it, applying H and distorting the result.
#include <opencv2/core.hpp>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack {

// Recorded reference pixels -> recorded frame pixels under H (between undistorted pixels of
// `camera`); without distortion this is transferPoint. referenceThroughLens false: the reference
// comes from another camera and is used as recorded (its pixels are mapped by H as they are;
// only the frame side is distorted). NaN for a point H sends to infinity or behind the camera
// (third homogeneous coordinate <= 0).
std::vector<cv::Point2d> transferThroughLens(const cv::Matx33d& H,
                                             const std::vector<cv::Point2d>& referencePixels,
                                             const PinholeCamera& camera,
                                             bool referenceThroughLens = true);

}  // namespace reftrack
