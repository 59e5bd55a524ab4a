#include "app/research/baselines/OpenCvFeatures.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::app {

OpenCvFeatures openCvFeatures(const std::string& name, int orbFeatures) {
  if (name == "sift") return {cv::SIFT::create(), cv::NORM_L2};
  if (name == "akaze") return {cv::AKAZE::create(), cv::NORM_HAMMING};
  if (name == "orb") return {cv::ORB::create(orbFeatures), cv::NORM_HAMMING};
  throw Error("feature detector must be 'sift', 'akaze' or 'orb', got '" + name + "'");
}

}  // namespace reftrack::app
