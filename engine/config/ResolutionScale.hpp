#pragma once
// The paper states its pixel distances and corner counts at 320x240. A length given at that
// resolution is multiplied by resolutionScale(size) = sqrt(area / (320 * 240)); a count by its
// square (the area ratio).
#include <cmath>
#include <opencv2/core.hpp>

namespace reftrack {

inline constexpr double kPaperImageWidth = 320.0;
inline constexpr double kPaperImageHeight = 240.0;

inline double resolutionScale(cv::Size imageSize) {
  return std::sqrt(static_cast<double>(imageSize.width) * imageSize.height /
                   (kPaperImageWidth * kPaperImageHeight));
}

}  // namespace reftrack
