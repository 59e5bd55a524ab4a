#include "engine/config/MapExtensionParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"

namespace reftrack {

void MapExtensionParams::check() const {
  requireFiniteInRange("extension.max_distance_m", maxDistanceMetres, 1e-4, 1000.0);
  requireFiniteInRange("extension.max_angle_deg", maxAngleDeg, 0.01, 180.0);
  requireIntInRange("extension.min_inliers", minInliers, 6, 1000000);
  requireFiniteInRange("extension.max_support_sd_px", maxSupportSdPx, 1e-4, 100.0);
  requireIntInRange("extension.match_references", matchReferences, 1, 1000);
  requireIntInRange("extension.min_overlap_points", minOverlapPoints, 0, 1000000);
  requireFiniteInRange("extension.max_epipolar_distance_px", maxEpipolarDistancePx, 0.01, 100.0);
  requireFiniteInRange("extension.max_reprojection_error_px", maxReprojectionErrorPx, 0.01, 100.0);
  requireIntInRange("extension.min_new_points", minNewPoints, 1, 1000000);
  requireIntInRange("extension.max_references", maxReferences, 2, 100000);
}

void MapExtensionParams::write(cv::FileStorage& fs) const {
  fs << "max_distance_m" << maxDistanceMetres << "max_angle_deg" << maxAngleDeg << "min_inliers"
     << minInliers << "max_support_sd_px" << maxSupportSdPx << "match_references" << matchReferences
     << "min_overlap_points" << minOverlapPoints << "max_epipolar_distance_px"
     << maxEpipolarDistancePx << "max_reprojection_error_px" << maxReprojectionErrorPx
     << "min_new_points" << minNewPoints << "max_references" << maxReferences;
}

void MapExtensionParams::read(const cv::FileNode& node) {
  const std::string s = "extension";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { MapExtensionParams{}.write(fs); });
  readConfigValue(node, s, "max_distance_m", maxDistanceMetres);
  readConfigValue(node, s, "max_angle_deg", maxAngleDeg);
  readConfigValue(node, s, "min_inliers", minInliers);
  readConfigValue(node, s, "max_support_sd_px", maxSupportSdPx);
  readConfigValue(node, s, "match_references", matchReferences);
  readConfigValue(node, s, "min_overlap_points", minOverlapPoints);
  readConfigValue(node, s, "max_epipolar_distance_px", maxEpipolarDistancePx);
  readConfigValue(node, s, "max_reprojection_error_px", maxReprojectionErrorPx);
  readConfigValue(node, s, "min_new_points", minNewPoints);
  readConfigValue(node, s, "max_references", maxReferences);
  check();
}

}  // namespace reftrack
