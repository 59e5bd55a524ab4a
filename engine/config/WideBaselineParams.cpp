#include "engine/config/WideBaselineParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"
#include "engine/config/ResolutionScale.hpp"

namespace reftrack {

template <class Self, class Field>
void WideBaselineParams::fields(Self& p, const Field& field) {
  field("dx", p.dx, Range{0, 10000})
      .help(
          "Wide-baseline candidates lie within +-dx pixels horizontally of the predicted position");
  field("dy", p.dy, Range{0, 10000})
      .help("Wide-baseline candidates lie within +-dy pixels vertically of the predicted position");
  field("n", p.halfWindow, Range{1, 32})
      .help("n: the warped correlation compares (2n+1) x (2n+1) pixels");
  field("min_score", p.minScore, Range{-1.0, 1.0})
      .help(
          "The best candidate is kept only above this warped NCC score; higher: fewer, surer "
          "matches");
  field("affine_neighbours", p.affineNeighbours, Range{3, 100})
      .help("Previous-frame matches that define each candidate's local affine map");
  field("reference_corners", p.referenceCornersAt320x240, Range{0, 1000000})
      .help(
          "Reference corners tried per reference and frame (at 320x240, scaled), 3D ones first; 0: "
          "all");
  field("frame_to_frame_corners", p.frameToFrameCornersAt320x240, Range{8, 1000000})
      .help(
          "Corners per frame matched frame-to-frame for the predicting homography (at 320x240, "
          "scaled)");
  field("frame_corner_quality", p.frameCornerQuality, Range{1e-9, 1.0})
      .help("6-DOF frames keep corners down to this fraction of the strongest Harris response");
  field("seed_search", p.seedSearchAt320x240, Range{1, 10000})
      .help(
          "Started from a given pose, search +-this around the map points' projections (pixels at "
          "320x240)");
  field("align_frame_side", p.alignFrameSide)
      .help("Align each match's warped reference window to the frame by Lucas-Kanade (sub-pixel)");
  field("align_half_window", p.alignHalfWindow, Range{1, 32})
      .help("n: the alignment's windows are (2n+1) x (2n+1) pixels");
  field("keypoint_points", p.keypointPointsAt320x240, Range{0, 1000000})
      .help("Keypoint-layer points also measured per frame (at 320x240, scaled); 0: off (slower)");
  field("keypoint_sigma_px", p.keypointSigmaPx, Range{1e-3, 100.0})
      .help("Assumed SD of a keypoint measurement (pixels), its weight in the pose");
  field("keypoint_half_window", p.keypointHalfWindow, Range{1, 32})
      .help("n: a keypoint's alignment window is (2n+1) x (2n+1) pixels");
}

template struct ParamSection<WideBaselineParams>;
template void WideBaselineParams::fields(const WideBaselineParams&, const FieldDescriber&);

namespace {
int scaledCount(int countAt320x240, cv::Size imageSize) {
  return std::max(1, static_cast<int>(std::lround(countAt320x240 * countScale(imageSize))));
}
}  // namespace

int WideBaselineParams::frameToFrameCornersFor(cv::Size imageSize) const {
  return scaledCount(frameToFrameCornersAt320x240, imageSize);
}

int WideBaselineParams::keypointPointsFor(cv::Size imageSize) const {
  return keypointPointsAt320x240 == 0 ? 0 : scaledCount(keypointPointsAt320x240, imageSize);
}

int WideBaselineParams::referenceCornersFor(cv::Size imageSize) const {
  return referenceCornersAt320x240 == 0 ? 0 : scaledCount(referenceCornersAt320x240, imageSize);
}

}  // namespace reftrack
