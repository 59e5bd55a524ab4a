#include "engine/config/RelocalisationParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/ParamFields.hpp"
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

template <class Self, class Field>
void RelocalisationParams::fields(Self& p, const Field& field) {
  field("enabled", p.enabled);
  field("keypoints", p.keypoints, OneOf{{"orb", "akaze", "sift"}});
  field("features_per_frame", p.featuresPerFrame, Range{50, 100000});
  field("sift_frame_scale", p.siftFrameScale, Range{0.25, 1.0});
  field("features_per_reference", p.featuresPerReference, Range{50, 100000});
  field("reference_finer_levels", p.referenceFinerLevels, Range{0, 8});
  field("frame_finer_levels", p.frameFinerLevels, Range{0, 8});
  field("ratio", p.ratio, Range{0.1, 1.0});
  field("references_to_match", p.referencesToMatch, Range{1, 10000});
  field("ransac_iterations", p.ransacIterations, Range{1, 1000000});
  field("reprojection_px", p.reprojectionPx, Range{0.1, 100.0});
  field("min_inliers", p.minInliers, Range{6, 100000});
  field("min_inlier_ratio", p.minInlierRatio, Range{0.0, 1.0});
  field("attempt_every_frames", p.attemptEveryFrames, Range{1, 10000});
  field("budget_ms_per_frame", p.budgetMsPerFrame, Range{0.0, 1e6});
  field("budget_burst_ms", p.budgetBurstMs, Range{0.0, 1e9});
  field("min_inlier_cells", p.minInlierCells, Range{1, 16});
  field("max_rotation_sigma_deg", p.maxRotationSigmaDeg, Range{0.0, 180.0});
  field("max_position_sigma_ratio", p.maxPositionSigmaRatio, Range{0.0, 10.0});
  field("min_distinctive_inliers", p.minDistinctiveInliers, Range{0, 100000});
  field("min_keypoint_support", p.minKeypointSupport, Range{0, 100000});
  field("min_keypoint_agreement", p.minKeypointAgreement, Range{0.0, 1.0});
  field("triangulation_px", p.triangulationPx, Range{0.05, 100.0});
  field("min_parallax_deg", p.minParallaxDeg, Range{0.0, 90.0});
}

template struct ParamSection<RelocalisationParams>;

}  // namespace reftrack
