#include "engine/config/HomographyTrackerParams.hpp"

#include "engine/config/ConfigValue.hpp"
#include "engine/config/KnownKeys.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

std::string keypointLayerName(KeypointLayer layer) {
  switch (layer) {
    case KeypointLayer::None:
      return "none";
    case KeypointLayer::Orb:
      return "orb";
    case KeypointLayer::Akaze:
      return "akaze";
    case KeypointLayer::Sift:
      return "sift";
  }
  return "none";
}

KeypointLayer parseKeypointLayer(const std::string& name) {
  for (KeypointLayer k :
       {KeypointLayer::None, KeypointLayer::Orb, KeypointLayer::Akaze, KeypointLayer::Sift})
    if (keypointLayerName(k) == name) return k;
  throw Error("parameter 'homography.keypoints' must be 'orb', 'akaze', 'sift' or 'none', got '" +
              name + "'");
}

void HomographyTrackerParams::check() const {
  requireFiniteInRange("homography.guided_search_half_size_px", guidedSearchHalfSizePx, 0.5,
                       10000.0);
  requireFiniteInRange("homography.reacquire_corner_factor", reacquireCornerFactor, 1.0, 16.0);
  requireFiniteInRange("homography.reacquire_corner_quality", reacquireCornerQuality, 1e-6, 1.0);
  requireFiniteInRange("homography.reacquire_min_distance_px", reacquireMinDistancePx, 1.0, 1000.0);
  requireFiniteInRange("homography.frame_corner_factor", frameCornerFactor, 1.0, 16.0);
  requireIntInRange("homography.keypoint_features", keypointFeatures, 8, 100000);
  requireFiniteInRange("homography.keypoint_ratio", keypointRatio, 0.1, 1.0);
  requireFiniteInRange("homography.keypoint_detect_scale", keypointDetectScale, 0.1, 1.0);
  requireFiniteInRange("homography.keypoint_inlier_threshold_px", keypointInlierThresholdPx, 0.1,
                       100.0);
  requireFiniteInRange("homography.keypoint_search_half_size_px", keypointSearchHalfSizePx, 0.5,
                       100.0);
  if (refinePoints != 0) requireIntInRange("homography.refine_points", refinePoints, 8, 100000);
  requireIntInRange("homography.keypoint_tilt_views", keypointTiltViews, 0, 16);
  requireIntInRange("homography.keypoint_confident_inliers", keypointConfidentInliers, 4, 100000);
}

void HomographyTrackerParams::write(cv::FileStorage& fs) const {
  fs << "guided_search_half_size_px" << guidedSearchHalfSizePx << "frame_to_frame_prediction"
     << (frameToFramePrediction ? "true" : "false") << "reacquire_whole_image"
     << (reacquireWholeImage ? "true" : "false") << "reacquire_corner_factor"
     << reacquireCornerFactor << "reacquire_corner_quality" << reacquireCornerQuality
     << "reacquire_min_distance_px" << reacquireMinDistancePx << "frame_corner_factor"
     << frameCornerFactor << "rotation_model" << (rotationModel ? "true" : "false") << "keypoints"
     << keypointLayerName(keypoints) << "keypoint_features" << keypointFeatures << "keypoint_ratio"
     << keypointRatio << "keypoint_detect_scale" << keypointDetectScale
     << "keypoint_inlier_threshold_px" << keypointInlierThresholdPx
     << "keypoint_search_half_size_px" << keypointSearchHalfSizePx << "refine_points"
     << refinePoints << "keypoint_tilt_views" << keypointTiltViews << "keypoint_confident_inliers"
     << keypointConfidentInliers;
}

void HomographyTrackerParams::read(const cv::FileNode& node) {
  const std::string s = "homography";
  requireKeysWrittenBy(node, s, [](cv::FileStorage& fs) { HomographyTrackerParams{}.write(fs); });
  readConfigValue(node, s, "guided_search_half_size_px", guidedSearchHalfSizePx);
  readConfigValue(node, s, "frame_to_frame_prediction", frameToFramePrediction);
  readConfigValue(node, s, "reacquire_whole_image", reacquireWholeImage);
  readConfigValue(node, s, "reacquire_corner_factor", reacquireCornerFactor);
  readConfigValue(node, s, "reacquire_corner_quality", reacquireCornerQuality);
  readConfigValue(node, s, "reacquire_min_distance_px", reacquireMinDistancePx);
  readConfigValue(node, s, "frame_corner_factor", frameCornerFactor);
  readConfigValue(node, s, "rotation_model", rotationModel);
  std::string layer = keypointLayerName(keypoints);
  readConfigValue(node, s, "keypoints", layer);
  keypoints = parseKeypointLayer(layer);
  readConfigValue(node, s, "keypoint_features", keypointFeatures);
  readConfigValue(node, s, "keypoint_ratio", keypointRatio);
  readConfigValue(node, s, "keypoint_detect_scale", keypointDetectScale);
  readConfigValue(node, s, "keypoint_inlier_threshold_px", keypointInlierThresholdPx);
  readConfigValue(node, s, "keypoint_search_half_size_px", keypointSearchHalfSizePx);
  readConfigValue(node, s, "refine_points", refinePoints);
  readConfigValue(node, s, "keypoint_tilt_views", keypointTiltViews);
  readConfigValue(node, s, "keypoint_confident_inliers", keypointConfidentInliers);
  check();
}

}  // namespace reftrack
