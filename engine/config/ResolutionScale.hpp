#pragma once
// The paper states its pixel distances and corner counts at 320x240. A length given at that
// resolution is multiplied by resolutionScale(size) = sqrt(area / (320 * 240)); a count by
// countScale(size): the area ratio up to 640x480, and beyond it 4 times the side ratio to 640x480
// (2 sqrt(area ratio)). Above 640x480 an area-scaled count made the per-frame cost grow with the
// area (the matching's faster still), while each corner is already localised to a fraction of a
// pixel: measured with `reftrack experiment-6dof` and `bench-homography` (README, HD speed).
#include <cmath>
#include <opencv2/core.hpp>

namespace reftrack {

inline constexpr double kPaperImageWidth = 320.0;
inline constexpr double kPaperImageHeight = 240.0;

inline double resolutionScale(cv::Size imageSize) {
  return std::sqrt(static_cast<double>(imageSize.width) * imageSize.height /
                   (kPaperImageWidth * kPaperImageHeight));
}

inline double countScale(cv::Size imageSize) {
  const double areaRatio = static_cast<double>(imageSize.width) * imageSize.height /
                           (kPaperImageWidth * kPaperImageHeight);
  return areaRatio <= 4.0 ? areaRatio : 2.0 * std::sqrt(areaRatio);
}

}  // namespace reftrack
