#include "engine/config/CornerParams.hpp"

#include <algorithm>
#include <cmath>

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"
#include "engine/config/ResolutionScale.hpp"

namespace reftrack {

int CornerParams::countFor(cv::Size imageSize) const {
  return std::max(4, static_cast<int>(std::lround(countAt320x240 * countScale(imageSize))));
}

double CornerParams::minDistanceFor(cv::Size imageSize) const {
  return minDistancePx * resolutionScale(imageSize);
}

template <class Self, class Field>
void CornerParams::fields(Self& p, const Field& field) {
  field("count", p.countAt320x240, Range{4, 100000})
      .help(
          "Corners detected per image at 320x240 (scaled with the image); more: steadier poses, "
          "slower frames");
  field("quality", p.quality, Range{1e-6, 1.0})
      .help(
          "Weakest corner kept, as a fraction of the strongest Harris response; smaller: more, "
          "weaker corners");
  field("min_distance_px", p.minDistancePx, Range{0.0, 1000.0})
      .help("Minimum spacing between corners (pixels at 320x240, scaled); smaller: denser corners");
  field("harris_k", p.harrisK, Range{1e-4, 0.25})
      .help("Harris detector constant k; larger: fewer edge-like corners");
  field("block_size", p.blockSize, OddRange{3, 31})
      .help(
          "Harris structure-tensor window side (pixels, odd); larger: smoother, coarser response");
  field("fast_threshold", p.fastThreshold, Range{1, 255})
      .help(
          "FAST candidate threshold (grey levels, halved when too few are found); smaller: more "
          "candidates");
  field("detect_at_paper_scale", p.detectAtPaperScale)
      .help(
          "Find candidates on the pyramid level nearest 320x240 (refined at full size); false: at "
          "full size");
  field("grid_columns", p.gridColumns, Range{1, 64})
      .help("Corners are spread over a grid of this many columns, each cell getting its share");
  field("grid_rows", p.gridRows, Range{1, 64})
      .help("Rows of the grid the corners are spread over (see grid_columns)");
  field("subpixel_half_window", p.subPixelHalfWindow, Range{1, 15})
      .help("Half side of the sub-pixel corner refinement window (pixels)");
  field("contrast_window", p.contrastWindow, OddRange{3, 101})
      .help("Side of the RMS contrast window around each corner (pixels, odd; paper: 15)");
}

template struct ParamSection<CornerParams>;
template void CornerParams::fields(const CornerParams&, const FieldDescriber&);

}  // namespace reftrack
