#include "engine/config/RansacParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"

namespace reftrack {

void RansacParams::check() const {
  requireIntInRange("ransac.max_iterations", maxIterations, 1, 1000000);
  requireFiniteInRange("ransac.early_accept_support", earlyAcceptSupport, 0.0, 1.0);
  requireIntInRange("ransac.early_accept_min_iterations", earlyAcceptMinIterations, 1, 1000000);
  requireFiniteInRange("ransac.min_sample_spacing_px", minSampleSpacingPx, 0.0, 10000.0);
  requireFiniteInRange("ransac.min_determinant", minDeterminant, 1e-12, 1.0);
  requireFiniteInRange("ransac.min_inlier_ratio", minInlierRatio, 0.0, 1.0);
  requireIntInRange("ransac.min_inliers", minInliers, 4, 1000000);
  requireFiniteInRange("ransac.inlier_threshold_px", inlierThresholdPx, 1e-6, 1000.0);
  requireIntInRange("ransac.seed", seed, 0, 2147483647);
}

void RansacParams::write(cv::FileStorage& fs) const {
  fs << "max_iterations" << maxIterations << "early_accept_support" << earlyAcceptSupport
     << "early_accept_min_iterations" << earlyAcceptMinIterations << "min_sample_spacing_px"
     << minSampleSpacingPx << "min_determinant" << minDeterminant << "min_inlier_ratio"
     << minInlierRatio << "min_inliers" << minInliers << "inlier_threshold_px" << inlierThresholdPx
     << "refine" << (refine ? "true" : "false") << "seed" << seed << "progressive_sampling"
     << (progressiveSampling ? "true" : "false");
}

void RansacParams::read(const cv::FileNode& node) {
  const std::string s = "ransac";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { RansacParams{}.write(fs); });
  readConfigValue(node, s, "max_iterations", maxIterations);
  readConfigValue(node, s, "early_accept_support", earlyAcceptSupport);
  readConfigValue(node, s, "early_accept_min_iterations", earlyAcceptMinIterations);
  readConfigValue(node, s, "min_sample_spacing_px", minSampleSpacingPx);
  readConfigValue(node, s, "min_determinant", minDeterminant);
  readConfigValue(node, s, "min_inlier_ratio", minInlierRatio);
  readConfigValue(node, s, "min_inliers", minInliers);
  readConfigValue(node, s, "inlier_threshold_px", inlierThresholdPx);
  readConfigValue(node, s, "refine", refine);
  readConfigValue(node, s, "seed", seed);
  readConfigValue(node, s, "progressive_sampling", progressiveSampling);
  check();
}

}  // namespace reftrack
