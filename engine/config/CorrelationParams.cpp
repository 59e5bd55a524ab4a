#include "engine/config/CorrelationParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"

namespace reftrack {

void CorrelationParams::check() const {
  requireIntInRange("correlation.half_window", halfWindow, 1, 32);
  requireFiniteInRange("correlation.min_score", minScore, -1.0, 1.0);
  requireFiniteInRange("correlation.search_half_width_px", searchHalfWidthPx, 0.0, 100000.0);
  requireFiniteInRange("correlation.search_half_height_px", searchHalfHeightPx, 0.0, 100000.0);
}

void CorrelationParams::write(cv::FileStorage& fs) const {
  fs << "half_window" << halfWindow << "min_score" << minScore << "search_half_width_px"
     << searchHalfWidthPx << "search_half_height_px" << searchHalfHeightPx << "symmetric_check"
     << (symmetricCheck ? "true" : "false");
}

void CorrelationParams::read(const cv::FileNode& node) {
  const std::string s = "correlation";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { CorrelationParams{}.write(fs); });
  readConfigValue(node, s, "half_window", halfWindow);
  readConfigValue(node, s, "min_score", minScore);
  readConfigValue(node, s, "search_half_width_px", searchHalfWidthPx);
  readConfigValue(node, s, "search_half_height_px", searchHalfHeightPx);
  readConfigValue(node, s, "symmetric_check", symmetricCheck);
  check();
}

}  // namespace reftrack
