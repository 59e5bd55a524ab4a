#include "engine/geometry/FrameUndistorter.hpp"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack {

FrameUndistorter::FrameUndistorter(const PinholeCamera& camera) : camera_(camera) {
  camera_.check();
  if (!camera_.hasDistortion()) return;
  // Fixed-point maps (cv::remap interpolates at 1/32 px either way).
  cv::initUndistortRectifyMap(camera_.Kcv(), camera_.distortion(), cv::noArray(), camera_.Kcv(),
                              camera_.imageSize(), CV_16SC2, mapXY_, mapFraction_);
}

cv::Mat FrameUndistorter::undistort(const cv::Mat& image) const {
  if (image.size() != camera_.imageSize())
    throw Error("undistort: the image is " + std::to_string(image.cols) + "x" +
                std::to_string(image.rows) + " but the camera is calibrated for " +
                std::to_string(camera_.imageSize().width) + "x" +
                std::to_string(camera_.imageSize().height));
  if (mapXY_.empty()) return image;
  cv::Mat out;
  cv::remap(image, out, mapXY_, mapFraction_, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  return out;
}

}  // namespace reftrack
