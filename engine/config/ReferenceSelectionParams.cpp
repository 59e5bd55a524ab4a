#include "engine/config/ReferenceSelectionParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"

namespace reftrack {

void ReferenceSelectionParams::check() const {
  requireFiniteInRange("references.angle_weight", angleWeight, 0.0, 1e6);
  requireIntInRange("references.min_shared_points", minSharedPoints, 6, 1000000);
  requireFiniteInRange("references.switch_margin", switchMargin, 0.0, 0.99);
  requireIntInRange("references.switch_after_frames", switchAfterFrames, 1, 1000000);
  requireIntInRange("references.cached_trackers", cachedTrackers, 1, 1000);
  requireIntInRange("references.reseed_frames", reseedFrames, 0, 1000000);
}

void ReferenceSelectionParams::write(cv::FileStorage& fs) const {
  fs << "angle_weight" << angleWeight << "min_shared_points" << minSharedPoints << "switch_margin"
     << switchMargin << "switch_after_frames" << switchAfterFrames << "cached_trackers"
     << cachedTrackers << "reseed_frames" << reseedFrames;
}

void ReferenceSelectionParams::read(const cv::FileNode& node) {
  const std::string s = "references";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { ReferenceSelectionParams{}.write(fs); });
  readConfigValue(node, s, "angle_weight", angleWeight);
  readConfigValue(node, s, "min_shared_points", minSharedPoints);
  readConfigValue(node, s, "switch_margin", switchMargin);
  readConfigValue(node, s, "switch_after_frames", switchAfterFrames);
  readConfigValue(node, s, "cached_trackers", cachedTrackers);
  readConfigValue(node, s, "reseed_frames", reseedFrames);
  check();
}

}  // namespace reftrack
