#include "engine/config/UnpreparedMapParams.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void UnpreparedMapParams::fields(Self& p, const Field& field) {
  field("keypoints", p.keypoints, OneOf{{"orb", "akaze", "sift"}})
      .help("Keypoints matched between the two views to find their relative pose");
  field("max_keypoints", p.maxKeypoints, Range{50, 100000})
      .help("Keypoints kept per view (the strongest)");
  field("ratio", p.ratio, Range{0.1, 1.0}).help("Lowe's ratio test of the keypoint matches");
  field("min_keypoints", p.minKeypoints, Range{8, 100000})
      .help("A view with fewer keypoints is refused as textureless");
  field("min_matches", p.minMatches, Range{8, 100000})
      .help("A pair with fewer keypoint matches is refused (too little shared view)");
  field("ransac_threshold_px", p.ransacThresholdPx, Range{0.05, 20.0})
      .help("Essential-matrix RANSAC: largest distance of an inlier to its epipolar line (pixels)");
  field("min_inliers", p.minInliers, Range{8, 100000})
      .help("A pair whose essential matrix has fewer inliers is refused");
  field("max_rotation_share", p.maxRotationShare, Range{0.0, 1.0})
      .help(
          "Refused as a pure rotation when a rotation alone explains this share of the "
          "essential matrix's inliers");
  field("min_parallax_deg", p.minParallaxDeg, Range{0.0, 90.0})
      .help("Refused when the inliers' median angle between the two viewing rays is below this");
  field("bootstrap_epipolar_distance_px", p.bootstrapEpipolarDistancePx, Range{0.1, 100.0})
      .help("Epipolar gate of the first corner matching, on the essential matrix's pose (pixels)");
  field("bootstrap_reprojection_error_px", p.bootstrapReprojectionErrorPx, Range{0.1, 100.0})
      .help("Reprojection gate of that matching (pixels)");
  field("refinement_rounds", p.refinementRounds, Range{1, 10})
      .help("Rounds of corner matching and pose refinement before the final preparation");
}

template struct ParamSection<UnpreparedMapParams>;
template void UnpreparedMapParams::fields(const UnpreparedMapParams&, const FieldDescriber&);

}  // namespace reftrack
