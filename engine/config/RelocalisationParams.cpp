#include "engine/config/RelocalisationParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/FieldDescriber.hpp"
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
  field("enabled", p.enabled)
      .help(
          "Start and re-start from any view with the map's keypoints; false: only near a "
          "reference");
  field("keypoints", p.keypoints, OneOf{{"orb", "akaze", "sift"}})
      .help("Keypoint detector and descriptor of the map's keypoint layer");
  field("features_per_frame", p.featuresPerFrame, Range{50, 100000})
      .help(
          "Keypoints detected per frame (at 640x480, scaled with the area); more: more views "
          "found, slower");
  field("sift_frame_scale", p.siftFrameScale, Range{0.25, 1.0})
      .help(
          "SIFT only: a frame is reduced by this factor before detection; smaller: faster, fewer "
          "views found");
  field("features_per_reference", p.featuresPerReference, Range{50, 100000})
      .help("Keypoints stored per reference (at 640x480, scaled with the area)");
  field("reference_finer_levels", p.referenceFinerLevels, Range{0, 8})
      .help("ORB only: pyramid levels above each reference image (1.2x each) for closer views");
  field("frame_finer_levels", p.frameFinerLevels, Range{0, 8})
      .help(
          "ORB only: a frame giving no pose is detected again with this many finer levels; 0: not");
  field("ratio", p.ratio, Range{0.1, 1.0})
      .help("Lowe's ratio test on the two nearest descriptors; lower: stricter");
  field("references_to_match", p.referencesToMatch, Range{1, 10000})
      .help("Only the best-voted this many references are matched; more: slower");
  field("ransac_iterations", p.ransacIterations, Range{1, 1000000}).help("PnP-RANSAC iterations");
  field("reprojection_px", p.reprojectionPx, Range{0.1, 100.0})
      .help("PnP-RANSAC inlier threshold (pixels at 320x240, scaled)");
  field("min_inliers", p.minInliers, Range{6, 100000})
      .help("Fewer PnP inliers than this: no candidate pose");
  field("min_inlier_ratio", p.minInlierRatio, Range{0.0, 1.0})
      .help("Inliers / 2D-3D matches below this: no candidate pose");
  field("attempt_every_frames", p.attemptEveryFrames, Range{1, 10000})
      .help("While lost, try on every n-th frame only (saves time)");
  field("budget_ms_per_frame", p.budgetMsPerFrame, Range{0.0, 1e6})
      .help(
          "While lost, the search's average ms per frame (modelled work on recorded input, CPU "
          "live)");
  field("budget_burst_ms", p.budgetBurstMs, Range{0.0, 1e9})
      .help(
          "... after a burst of this much (ms), refilled when tracking: the first searches come at "
          "once");
  field("resemblance_min_score", p.resemblanceMinScore, Range{0.0, 1.0})
      .help(
          "While lost, a frame correlating this much with a reference's small image looks like "
          "the scene; 0: off");
  field("budget_reserve_share", p.budgetReserveShare, Range{0.0, 0.99})
      .help("... and may spend this share of the burst, kept for such frames (0: none kept)");
  field("min_inlier_cells", p.minInlierCells, Range{1, 16})
      .help("The inliers must cover at least this many cells of a 4x4 grid over the frame");
  field("max_rotation_sigma_deg", p.maxRotationSigmaDeg, Range{0.0, 180.0})
      .help("Refuse a pose whose predicted rotation SD exceeds this (degrees)");
  field("max_position_sigma_ratio", p.maxPositionSigmaRatio, Range{0.0, 10.0})
      .help(
          "Refuse a pose whose predicted position SD exceeds this fraction of the inliers' depth");
  field("min_distinctive_inliers", p.minDistinctiveInliers, Range{0, 100000})
      .help(
          "A start needs this many confirmed matches to distinctive reference corners (no "
          "look-alike)");
  field("min_keypoint_support", p.minKeypointSupport, Range{0, 100000})
      .help(
          "With a keypoint layer, a start also needs this many keypoint matches agreeing; 0: no "
          "check");
  field("min_keypoint_agreement", p.minKeypointAgreement, Range{0.0, 1.0})
      .help(
          "With a keypoint layer, a start also needs this share of its keypoint matches agreeing");
  field("triangulation_px", p.triangulationPx, Range{0.05, 100.0})
      .help(
          "Preparation: a keypoint gets a 3D point when it reprojects this close in both views (px "
          "at 320x240)");
  field("min_parallax_deg", p.minParallaxDeg, Range{0.0, 90.0})
      .help(
          "Preparation: a keypoint gets a 3D point only when its two rays meet at this angle "
          "(degrees)");
}

template struct ParamSection<RelocalisationParams>;
template void RelocalisationParams::fields(const RelocalisationParams&, const FieldDescriber&);

}  // namespace reftrack
