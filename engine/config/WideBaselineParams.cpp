#include "engine/config/WideBaselineParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/ParamFields.hpp"
#include "engine/config/ResolutionScale.hpp"

namespace reftrack {

template <class Self, class Field>
void WideBaselineParams::fields(Self& p, const Field& field) {
  field("dx", p.dx, Range{0, 10000});
  field("dy", p.dy, Range{0, 10000});
  field("n", p.halfWindow, Range{1, 32});
  field("min_score", p.minScore, Range{-1.0, 1.0});
  field("affine_neighbours", p.affineNeighbours, Range{3, 100});
  field("reference_corners", p.referenceCornersAt320x240, Range{0, 1000000});
  field("frame_to_frame_corners", p.frameToFrameCornersAt320x240, Range{8, 1000000});
  field("frame_corner_quality", p.frameCornerQuality, Range{1e-9, 1.0});
  field("seed_search", p.seedSearchAt320x240, Range{1, 10000});
  field("align_frame_side", p.alignFrameSide);
  field("align_half_window", p.alignHalfWindow, Range{1, 32});
  field("keypoint_points", p.keypointPointsAt320x240, Range{0, 1000000});
  field("keypoint_sigma_px", p.keypointSigmaPx, Range{1e-3, 100.0});
  field("keypoint_half_window", p.keypointHalfWindow, Range{1, 32});
}

template struct ParamSection<WideBaselineParams>;

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
