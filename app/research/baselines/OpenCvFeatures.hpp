#pragma once
// openCvFeatures: the OpenCV keypoint detector + descriptor named "sift", "akaze" or "orb" (ORB
// with `orbFeatures` features; SIFT and AKAZE with OpenCV's defaults) and the norm its
// descriptors are compared with (L2 for SIFT, Hamming for the binary ones). Shared by the
// baselines that stand for "what a user would write with OpenCV alone".
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <string>

namespace reftrack::app {

struct OpenCvFeatures {
  cv::Ptr<cv::Feature2D> detector;
  int norm = cv::NORM_HAMMING;
};

// Throws reftrack::Error naming the accepted names for any other `name`.
OpenCvFeatures openCvFeatures(const std::string& name, int orbFeatures = 1000);

}  // namespace reftrack::app
