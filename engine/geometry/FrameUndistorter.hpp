#pragma once
// FrameUndistorter: removes a camera's lens distortion from whole frames through a remap
// computed once (cv::initUndistortRectifyMap, the same K and image size), so straight lines
// come out straight and two views of a plane, or of a rotating camera, are related by a
// homography. Points go both ways with PinholeCamera::undistortPixels / distortPixels.
#include <opencv2/core.hpp>

#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack {

class FrameUndistorter {
 public:
  // Throws reftrack::Error when the camera fails check().
  explicit FrameUndistorter(const PinholeCamera& camera);

  const PinholeCamera& camera() const { return camera_; }
  // Bilinear remap of an image of the camera's size (any type cv::remap takes); the image itself
  // when the camera has no distortion. Throws reftrack::Error on another size.
  cv::Mat undistort(const cv::Mat& image) const;

 private:
  PinholeCamera camera_;
  cv::Mat mapXY_, mapFraction_;  // cv::remap's fixed-point maps (CV_16SC2 + CV_16UC1)
};

}  // namespace reftrack
