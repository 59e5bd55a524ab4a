#include "engine/config/HomographyTrackerParams.hpp"

#include "engine/config/FieldDescriber.hpp"
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
  field("guided_search_half_size_px", p.guidedSearchHalfSizePx, Range{0.5, 10000.0})
      .help(
          "Matches are searched within +-this of their predicted position (pixels at 320x240, "
          "scaled)");
  field("frame_to_frame_prediction", p.frameToFramePrediction)
      .help(
          "Predict with the frame-to-frame homography chained with the last one; false: the last "
          "one alone");
  field("reacquire_whole_image", p.reacquireWholeImage)
      .help(
          "While lost, match reference corners over the whole frame; false: within the correlation "
          "search");
  field("reacquire_corner_factor", p.reacquireCornerFactor, Range{1.0, 16.0})
      .help(
          "While lost, match with this many times the corner count (frames barely overlapping the "
          "reference)");
  field("reacquire_corner_quality", p.reacquireCornerQuality, Range{1e-6, 1.0})
      .help("While lost, corners down to this fraction of the strongest Harris response");
  field("reacquire_min_distance_px", p.reacquireMinDistancePx, Range{1.0, 1000.0})
      .help("While lost, corners this close to each other (pixels at 320x240, scaled)");
  field("frame_corner_factor", p.frameCornerFactor, Range{1.0, 16.0})
      .help(
          "While tracking, each frame is searched with this many times the reference's corner "
          "count");
  field("rotation_model", p.rotationModel)
      .help(
          "With a calibrated camera, retry a frame that fails with the rotation-only model H = K R "
          "K^-1");
  field("keypoints", p.keypoints, TextForm<KeypointLayer>{keypointLayerName, parseKeypointLayer})
      .help(
          "Keypoints that register far views cold (first frame, after a loss); none: correlation "
          "matching only");
  field("keypoint_features", p.keypointFeatures, Range{8, 100000})
      .help("Keypoints kept per image (the strongest); more: more far views registered, slower");
  field("keypoint_ratio", p.keypointRatio, Range{0.1, 1.0})
      .help(
          "Lowe's ratio test: a keypoint match is kept below this fraction of the second-best "
          "distance");
  field("keypoint_detect_scale", p.keypointDetectScale, Range{0.1, 1.0})
      .help(
          "Frame keypoints are detected at this fraction of its resolution (1: full); smaller: "
          "faster");
  field("keypoint_inlier_threshold_px", p.keypointInlierThresholdPx, Range{0.1, 100.0})
      .help("Inlier threshold of the keypoint homography (pixels at 320x240, scaled)");
  field("keypoint_search_half_size_px", p.keypointSearchHalfSizePx, Range{0.5, 100.0})
      .help(
          "Around the keypoint homography, warped windows are searched within +-this (pixels at "
          "320x240)");
  field("refine_points", p.refinePoints, OffOrRange{8, 100000})
      .help(
          "Refine every registered homography by Lucas-Kanade at this many points per 320x240 "
          "(scaled); 0: off");
  field("keypoint_tilt_views", p.keypointTiltViews, Range{0, 16})
      .help(
          "Reference keypoints also from this many views tilted by 50 degrees (steep views, "
          "ASIFT-like); 0: off");
  field("keypoint_confident_inliers", p.keypointConfidentInliers, Range{4, 100000})
      .help(
          "The tilted views are matched only when the plain keypoints give fewer inliers than "
          "this");
  field("keypoint_steep_tilt_views", p.keypointSteepTiltViews, Range{0, 16})
      .help(
          "A second ring of this many views tilted by keypoint_steep_tilt_deg (views of 55-70 "
          "degrees); 0: off");
  field("keypoint_steep_tilt_deg", p.keypointSteepTiltDeg, Range{30.0, 80.0})
      .help("Tilt of the second ring of synthetic views (degrees)");
  field("keypoint_one_to_one", p.keypointOneToOne)
      .help(
          "Without a confident homography, match once more one-to-one (repeated patterns) with "
          "MAGSAC++");
  field("verify", p.verify)
      .help(
          "Check every cold registration by correlating warped reference points before reporting "
          "it; false: no check");
  field("verify_min_score", p.verifyMinScore, Range{-0.99, 0.99})
      .help("The check: a point's correlation peak counts from this NCC score");
  field("verify_search_px", p.verifySearchPx, Range{1.0, 50.0})
      .help("The check searches +-this around each mapped point (pixels at 320x240)");
  field("verify_tolerance_px", p.verifyTolerancePx, Range{0.05, 50.0})
      .help(
          "The check's inlier distance for the correction fitted to the peaks (pixels at 320x240)");
  field("verify_min_fraction", p.verifyMinFraction, Range{0.0, 1.0})
      .help("The check passes only when at least this fraction of the measurable points confirm");
  field("verify_min_spread", p.verifyMinSpread, Range{0.0, 1.0})
      .help("The check passes only when the confirming points cover this fraction of a 3x3 grid");
  field("verify_max_offset_px", p.verifyMaxOffsetPx, Range{0.001, 100.0})
      .help(
          "The check fails when its correction moves a textured point more than this (px at "
          "320x240)");
  field("verify_min_support", p.verifyMinSupport, Range{0.0, 1.0})
      .help(
          "The check compares the inliers' region only, and fails when it covers less than this "
          "fraction of the overlap");
}

template struct ParamSection<HomographyTrackerParams>;
template void HomographyTrackerParams::fields(const HomographyTrackerParams&,
                                              const FieldDescriber&);

}  // namespace reftrack
