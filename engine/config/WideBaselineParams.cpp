#include "engine/config/WideBaselineParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/config/ResolutionScale.hpp"

namespace reftrack {

void WideBaselineParams::check() const {
  requireIntInRange("wide_baseline.dx", dx, 0, 10000);
  requireIntInRange("wide_baseline.dy", dy, 0, 10000);
  requireIntInRange("wide_baseline.n", halfWindow, 1, 32);
  requireFiniteInRange("wide_baseline.min_score", minScore, -1.0, 1.0);
  requireIntInRange("wide_baseline.affine_neighbours", affineNeighbours, 3, 100);
  requireIntInRange("wide_baseline.reference_corners", referenceCornersAt320x240, 0, 1000000);
  requireIntInRange("wide_baseline.frame_to_frame_corners", frameToFrameCornersAt320x240, 8,
                    1000000);
  requireFiniteInRange("wide_baseline.frame_corner_quality", frameCornerQuality, 1e-9, 1.0);
  requireIntInRange("wide_baseline.seed_search", seedSearchAt320x240, 1, 10000);
}

namespace {
int scaledCount(int countAt320x240, cv::Size imageSize) {
  return std::max(1, static_cast<int>(std::lround(countAt320x240 * countScale(imageSize))));
}
}  // namespace

int WideBaselineParams::frameToFrameCornersFor(cv::Size imageSize) const {
  return scaledCount(frameToFrameCornersAt320x240, imageSize);
}

int WideBaselineParams::referenceCornersFor(cv::Size imageSize) const {
  return referenceCornersAt320x240 == 0 ? 0 : scaledCount(referenceCornersAt320x240, imageSize);
}

void WideBaselineParams::write(cv::FileStorage& fs) const {
  fs << "dx" << dx << "dy" << dy << "n" << halfWindow << "min_score" << minScore
     << "affine_neighbours" << affineNeighbours << "reference_corners" << referenceCornersAt320x240
     << "frame_to_frame_corners" << frameToFrameCornersAt320x240 << "frame_corner_quality"
     << frameCornerQuality << "seed_search" << seedSearchAt320x240;
}

void WideBaselineParams::read(const cv::FileNode& node) {
  const std::string s = "wide_baseline";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { WideBaselineParams{}.write(fs); });
  readConfigValue(node, s, "dx", dx);
  readConfigValue(node, s, "dy", dy);
  readConfigValue(node, s, "n", halfWindow);
  readConfigValue(node, s, "min_score", minScore);
  readConfigValue(node, s, "affine_neighbours", affineNeighbours);
  readConfigValue(node, s, "reference_corners", referenceCornersAt320x240);
  readConfigValue(node, s, "frame_to_frame_corners", frameToFrameCornersAt320x240);
  readConfigValue(node, s, "frame_corner_quality", frameCornerQuality);
  readConfigValue(node, s, "seed_search", seedSearchAt320x240);
  check();
}

}  // namespace reftrack
