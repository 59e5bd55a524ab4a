#include "engine/config/HomographyTrackerParams.hpp"

#include "engine/config/ParamFields.hpp"
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

template <class Self, class Field>
void HomographyTrackerParams::fields(Self& p, const Field& field) {
  field("guided_search_half_size_px", p.guidedSearchHalfSizePx, Range{0.5, 10000.0});
  field("frame_to_frame_prediction", p.frameToFramePrediction);
  field("reacquire_whole_image", p.reacquireWholeImage);
  field("reacquire_corner_factor", p.reacquireCornerFactor, Range{1.0, 16.0});
  field("reacquire_corner_quality", p.reacquireCornerQuality, Range{1e-6, 1.0});
  field("reacquire_min_distance_px", p.reacquireMinDistancePx, Range{1.0, 1000.0});
  field("frame_corner_factor", p.frameCornerFactor, Range{1.0, 16.0});
  field("rotation_model", p.rotationModel);
  field("keypoints", p.keypoints, TextForm<KeypointLayer>{keypointLayerName, parseKeypointLayer});
  field("keypoint_features", p.keypointFeatures, Range{8, 100000});
  field("keypoint_ratio", p.keypointRatio, Range{0.1, 1.0});
  field("keypoint_detect_scale", p.keypointDetectScale, Range{0.1, 1.0});
  field("keypoint_inlier_threshold_px", p.keypointInlierThresholdPx, Range{0.1, 100.0});
  field("keypoint_search_half_size_px", p.keypointSearchHalfSizePx, Range{0.5, 100.0});
  field("refine_points", p.refinePoints, OffOrRange{8, 100000});
  field("keypoint_tilt_views", p.keypointTiltViews, Range{0, 16});
  field("keypoint_confident_inliers", p.keypointConfidentInliers, Range{4, 100000});
  field("keypoint_steep_tilt_views", p.keypointSteepTiltViews, Range{0, 16});
  field("keypoint_steep_tilt_deg", p.keypointSteepTiltDeg, Range{30.0, 80.0});
  field("keypoint_one_to_one", p.keypointOneToOne);
  field("verify", p.verify);
  field("verify_min_score", p.verifyMinScore, Range{-0.99, 0.99});
  field("verify_search_px", p.verifySearchPx, Range{1.0, 50.0});
  field("verify_tolerance_px", p.verifyTolerancePx, Range{0.05, 50.0});
  field("verify_min_fraction", p.verifyMinFraction, Range{0.0, 1.0});
  field("verify_min_spread", p.verifyMinSpread, Range{0.0, 1.0});
  field("verify_max_offset_px", p.verifyMaxOffsetPx, Range{0.001, 100.0});
}

template struct ParamSection<HomographyTrackerParams>;

}  // namespace reftrack
