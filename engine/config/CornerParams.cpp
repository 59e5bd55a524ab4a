#include "engine/config/CornerParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/config/ResolutionScale.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

int CornerParams::countFor(cv::Size imageSize) const {
  return std::max(4, static_cast<int>(std::lround(countAt320x240 * countScale(imageSize))));
}

double CornerParams::minDistanceFor(cv::Size imageSize) const {
  return minDistancePx * resolutionScale(imageSize);
}

void CornerParams::check() const {
  requireIntInRange("corners.count", countAt320x240, 4, 100000);
  requireFiniteInRange("corners.quality", quality, 1e-6, 1.0);
  requireFiniteInRange("corners.min_distance_px", minDistancePx, 0.0, 1000.0);
  requireFiniteInRange("corners.harris_k", harrisK, 1e-4, 0.25);
  requireIntInRange("corners.block_size", blockSize, 3, 31);
  if (blockSize % 2 == 0) throw Error("parameter 'corners.block_size' must be odd");
  requireIntInRange("corners.fast_threshold", fastThreshold, 1, 255);
  requireIntInRange("corners.grid_columns", gridColumns, 1, 64);
  requireIntInRange("corners.grid_rows", gridRows, 1, 64);
  requireIntInRange("corners.subpixel_half_window", subPixelHalfWindow, 1, 15);
  requireIntInRange("corners.contrast_window", contrastWindow, 3, 101);
  if (contrastWindow % 2 == 0) throw Error("parameter 'corners.contrast_window' must be odd");
}

void CornerParams::write(cv::FileStorage& fs) const {
  fs << "count" << countAt320x240 << "quality" << quality << "min_distance_px" << minDistancePx
     << "harris_k" << harrisK << "block_size" << blockSize << "fast_threshold" << fastThreshold
     << "detect_at_paper_scale" << (detectAtPaperScale ? "true" : "false") << "grid_columns"
     << gridColumns << "grid_rows" << gridRows << "subpixel_half_window" << subPixelHalfWindow
     << "contrast_window" << contrastWindow;
}

void CornerParams::read(const cv::FileNode& node) {
  const std::string s = "corners";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { CornerParams{}.write(fs); });
  readConfigValue(node, s, "count", countAt320x240);
  readConfigValue(node, s, "quality", quality);
  readConfigValue(node, s, "min_distance_px", minDistancePx);
  readConfigValue(node, s, "harris_k", harrisK);
  readConfigValue(node, s, "block_size", blockSize);
  readConfigValue(node, s, "fast_threshold", fastThreshold);
  readConfigValue(node, s, "detect_at_paper_scale", detectAtPaperScale);
  readConfigValue(node, s, "grid_columns", gridColumns);
  readConfigValue(node, s, "grid_rows", gridRows);
  readConfigValue(node, s, "subpixel_half_window", subPixelHalfWindow);
  readConfigValue(node, s, "contrast_window", contrastWindow);
  check();
}

}  // namespace reftrack
