#include "engine/config/BundleAdjustmentParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

void BundleAdjustmentParams::check() const {
  if (loss != "huber" && loss != "cauchy" && loss != "none")
    throw Error("parameter 'bundle_adjustment.loss' must be cauchy, huber or none, got '" + loss +
                "'");
  requireFiniteInRange("bundle_adjustment.loss_scale_px", lossScalePx, 1e-3, 1000.0);
  requireFiniteInRange("bundle_adjustment.outlier_threshold_px", outlierThresholdPx, 1e-3, 1000.0);
  requireIntInRange("bundle_adjustment.max_iterations", maxIterations, 1, 100000);
  requireIntInRange("bundle_adjustment.min_determined_points", minDeterminedPoints, 3, 1000000);
}

void BundleAdjustmentParams::write(cv::FileStorage& fs) const {
  fs << "loss" << loss << "loss_scale_px" << lossScalePx << "outlier_threshold_px"
     << outlierThresholdPx << "max_iterations" << maxIterations << "min_determined_points"
     << minDeterminedPoints;
}

void BundleAdjustmentParams::read(const cv::FileNode& node) {
  const std::string s = "bundle_adjustment";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { BundleAdjustmentParams{}.write(fs); });
  readConfigValue(node, s, "loss", loss);
  readConfigValue(node, s, "loss_scale_px", lossScalePx);
  readConfigValue(node, s, "outlier_threshold_px", outlierThresholdPx);
  readConfigValue(node, s, "max_iterations", maxIterations);
  readConfigValue(node, s, "min_determined_points", minDeterminedPoints);
  check();
}

}  // namespace reftrack
