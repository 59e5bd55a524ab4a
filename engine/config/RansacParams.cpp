#include "engine/config/RansacParams.hpp"

#include "engine/config/ParamFields.hpp"

namespace reftrack {

template <class Self, class Field>
void RansacParams::fields(Self& p, const Field& field) {
  field("max_iterations", p.maxIterations, Range{1, 1000000});
  field("early_accept_support", p.earlyAcceptSupport, Range{0.0, 1.0});
  field("early_accept_min_iterations", p.earlyAcceptMinIterations, Range{1, 1000000});
  field("min_sample_spacing_px", p.minSampleSpacingPx, Range{0.0, 10000.0});
  field("min_determinant", p.minDeterminant, Range{1e-12, 1.0});
  field("min_inlier_ratio", p.minInlierRatio, Range{0.0, 1.0});
  field("min_inliers", p.minInliers, Range{4, 1000000});
  field("inlier_threshold_px", p.inlierThresholdPx, Range{1e-6, 1000.0});
  field("refine", p.refine);
  field("seed", p.seed, Range{0, 2147483647});
  field("progressive_sampling", p.progressiveSampling);
}

template struct ParamSection<RansacParams>;

}  // namespace reftrack
