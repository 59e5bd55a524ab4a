#include "engine/config/BundleAdjustmentParams.hpp"

#include "engine/config/ParamFields.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

template <class Self, class Field>
void BundleAdjustmentParams::fields(Self& p, const Field& field) {
  field("loss", p.loss, OneOf{{"cauchy", "huber", "none"}});
  field("loss_scale_px", p.lossScalePx, Range{1e-3, 1000.0});
  field("outlier_threshold_px", p.outlierThresholdPx, Range{1e-3, 1000.0});
  field("max_iterations", p.maxIterations, Range{1, 100000});
  field("min_determined_points", p.minDeterminedPoints, Range{3, 1000000});
}

template struct ParamSection<BundleAdjustmentParams>;

}  // namespace reftrack
