#include "engine/config/RelocalisationParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {
int scaledFrom640x480(int count, cv::Size size) {
  const double area = static_cast<double>(size.area()) / (640.0 * 480.0);
  return std::max(1, static_cast<int>(std::lround(count * area)));
}
}  // namespace

int RelocalisationParams::featuresPerFrameFor(cv::Size size) const {
  return scaledFrom640x480(featuresPerFrame, size);
}

int RelocalisationParams::featuresPerReferenceFor(cv::Size size) const {
  return scaledFrom640x480(featuresPerReference, size);
}

void RelocalisationParams::check() const {
  if (keypoints != "orb" && keypoints != "akaze" && keypoints != "sift")
    throw Error("relocalisation.keypoints must be 'orb', 'akaze' or 'sift', got '" + keypoints +
                "'");
  requireIntInRange("relocalisation.features_per_frame", featuresPerFrame, 50, 100000);
  requireIntInRange("relocalisation.features_per_reference", featuresPerReference, 50, 100000);
  requireIntInRange("relocalisation.reference_finer_levels", referenceFinerLevels, 0, 8);
  requireIntInRange("relocalisation.frame_finer_levels", frameFinerLevels, 0, 8);
  requireFiniteInRange("relocalisation.ratio", ratio, 0.1, 1.0);
  requireIntInRange("relocalisation.references_to_match", referencesToMatch, 1, 10000);
  requireIntInRange("relocalisation.ransac_iterations", ransacIterations, 1, 1000000);
  requireFiniteInRange("relocalisation.reprojection_px", reprojectionPx, 0.1, 100.0);
  requireIntInRange("relocalisation.min_inliers", minInliers, 6, 100000);
  requireFiniteInRange("relocalisation.min_inlier_ratio", minInlierRatio, 0.0, 1.0);
  requireIntInRange("relocalisation.attempt_every_frames", attemptEveryFrames, 1, 10000);
  requireIntInRange("relocalisation.min_inlier_cells", minInlierCells, 1, 16);
  requireFiniteInRange("relocalisation.max_rotation_sigma_deg", maxRotationSigmaDeg, 0.0, 180.0);
  requireFiniteInRange("relocalisation.max_position_sigma_ratio", maxPositionSigmaRatio, 0.0, 10.0);
  requireFiniteInRange("relocalisation.triangulation_px", triangulationPx, 0.05, 100.0);
  requireFiniteInRange("relocalisation.min_parallax_deg", minParallaxDeg, 0.0, 90.0);
}

void RelocalisationParams::write(cv::FileStorage& fs) const {
  fs << "enabled" << (enabled ? "true" : "false") << "keypoints" << keypoints
     << "features_per_frame" << featuresPerFrame << "features_per_reference" << featuresPerReference
     << "reference_finer_levels" << referenceFinerLevels << "frame_finer_levels" << frameFinerLevels
     << "ratio" << ratio << "references_to_match" << referencesToMatch << "ransac_iterations"
     << ransacIterations << "reprojection_px" << reprojectionPx << "min_inliers" << minInliers
     << "min_inlier_ratio" << minInlierRatio << "attempt_every_frames" << attemptEveryFrames
     << "min_inlier_cells" << minInlierCells << "max_rotation_sigma_deg" << maxRotationSigmaDeg
     << "max_position_sigma_ratio" << maxPositionSigmaRatio << "triangulation_px" << triangulationPx
     << "min_parallax_deg" << minParallaxDeg;
}

void RelocalisationParams::read(const cv::FileNode& node) {
  const std::string s = "relocalisation";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { RelocalisationParams{}.write(fs); });
  readConfigValue(node, s, "enabled", enabled);
  readConfigValue(node, s, "keypoints", keypoints);
  readConfigValue(node, s, "features_per_frame", featuresPerFrame);
  readConfigValue(node, s, "features_per_reference", featuresPerReference);
  readConfigValue(node, s, "reference_finer_levels", referenceFinerLevels);
  readConfigValue(node, s, "frame_finer_levels", frameFinerLevels);
  readConfigValue(node, s, "ratio", ratio);
  readConfigValue(node, s, "references_to_match", referencesToMatch);
  readConfigValue(node, s, "ransac_iterations", ransacIterations);
  readConfigValue(node, s, "reprojection_px", reprojectionPx);
  readConfigValue(node, s, "min_inliers", minInliers);
  readConfigValue(node, s, "min_inlier_ratio", minInlierRatio);
  readConfigValue(node, s, "attempt_every_frames", attemptEveryFrames);
  readConfigValue(node, s, "min_inlier_cells", minInlierCells);
  readConfigValue(node, s, "max_rotation_sigma_deg", maxRotationSigmaDeg);
  readConfigValue(node, s, "max_position_sigma_ratio", maxPositionSigmaRatio);
  readConfigValue(node, s, "triangulation_px", triangulationPx);
  readConfigValue(node, s, "min_parallax_deg", minParallaxDeg);
  check();
}

}  // namespace reftrack
