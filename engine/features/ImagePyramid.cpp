#include "engine/features/ImagePyramid.hpp"

#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"

namespace reftrack {

ImagePyramid::ImagePyramid(const cv::Mat& gray) {
  if (gray.empty() || gray.type() != CV_8UC1)
    throw Error("image pyramid: the image must be a non-empty 8-bit grey image");
  levels_.push_back(gray);
}

const cv::Mat& ImagePyramid::level(int level) const {
  if (level < 0) throw Error("image pyramid: level must be >= 0, got " + std::to_string(level));
  while (static_cast<int>(levels_.size()) <= level) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(std::move(next));
  }
  return levels_[static_cast<size_t>(level)];
}

}  // namespace reftrack
