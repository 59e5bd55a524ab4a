#pragma once
// FrameArray: a numpy image given to Tracker.track — uint8, H x W (grey), H x W x 1 or H x W x 3
// (BGR, as cv2.imread gives) — seen as a cv::Mat over the same memory when OpenCV can address it
// (pixels and channels contiguous within a row; any row stride, so row slices of a larger image
// too); any other layout (a transposed or column-strided view) is copied once. Another dtype or
// shape raises TypeError / ValueError naming what was given.
#include <pybind11/numpy.h>

#include <opencv2/core.hpp>

namespace reftrack::python {

struct FrameView {
  pybind11::array pixels;  // the caller's array, or its copy: keeps `mat`'s memory alive
  cv::Mat mat;
  bool copied = false;
};

FrameView viewFrame(const pybind11::handle& frame);

}  // namespace reftrack::python
