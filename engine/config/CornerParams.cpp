#include "engine/config/CornerParams.hpp"

#include <algorithm>
#include <cmath>

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
  field("count", p.countAt320x240, Range{4, 100000});
  field("quality", p.quality, Range{1e-6, 1.0});
  field("min_distance_px", p.minDistancePx, Range{0.0, 1000.0});
  field("harris_k", p.harrisK, Range{1e-4, 0.25});
  field("block_size", p.blockSize, OddRange{3, 31});
  field("fast_threshold", p.fastThreshold, Range{1, 255});
  field("detect_at_paper_scale", p.detectAtPaperScale);
  field("grid_columns", p.gridColumns, Range{1, 64});
  field("grid_rows", p.gridRows, Range{1, 64});
  field("subpixel_half_window", p.subPixelHalfWindow, Range{1, 15});
  field("contrast_window", p.contrastWindow, OddRange{3, 101});
}

template struct ParamSection<CornerParams>;

}  // namespace reftrack
