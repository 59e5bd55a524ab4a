#include "engine/config/WideBaselineParams.hpp"

#include "engine/config/ConfigValue.hpp"

namespace reftrack {

void WideBaselineParams::check() const {
  requireIntInRange("wide_baseline.dx", dx, 0, 10000);
  requireIntInRange("wide_baseline.dy", dy, 0, 10000);
  requireIntInRange("wide_baseline.n", halfWindow, 1, 32);
  requireFiniteInRange("wide_baseline.min_score", minScore, -1.0, 1.0);
  requireIntInRange("wide_baseline.affine_neighbours", affineNeighbours, 3, 100);
}

void WideBaselineParams::write(cv::FileStorage& fs) const {
  fs << "dx" << dx << "dy" << dy << "n" << halfWindow << "min_score" << minScore
     << "affine_neighbours" << affineNeighbours;
}

void WideBaselineParams::read(const cv::FileNode& node) {
  const std::string s = "wide_baseline";
  readConfigValue(node, s, "dx", dx);
  readConfigValue(node, s, "dy", dy);
  readConfigValue(node, s, "n", halfWindow);
  readConfigValue(node, s, "min_score", minScore);
  readConfigValue(node, s, "affine_neighbours", affineNeighbours);
  check();
}

}  // namespace reftrack
