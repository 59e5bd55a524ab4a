#include "engine/config/BundleAdjustmentParams.hpp"

#include "engine/config/FieldDescriber.hpp"
#include "engine/config/ParamFields.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

template <class Self, class Field>
void BundleAdjustmentParams::fields(Self& p, const Field& field) {
  field("loss", p.loss, OneOf{{"cauchy", "huber", "none"}})
      .help(
          "Robust loss on reprojection errors: cauchy (outliers fade), huber (bounded pull) or "
          "none");
  field("loss_scale_px", p.lossScalePx, Range{1e-3, 1000.0})
      .help("Errors up to this are weighed quadratically (pixels of the map's images)");
  field("outlier_threshold_px", p.outlierThresholdPx, Range{1e-3, 1000.0})
      .help("Errors above this count as outliers in the report (pixels; they stay in the map)");
  field("max_iterations", p.maxIterations, Range{1, 100000})
      .help("The adjustment stops after this many iterations");
  field("min_determined_points", p.minDeterminedPoints, Range{3, 1000000})
      .help("A reference is refined only when it sees this many points of determined references");
}

template struct ParamSection<BundleAdjustmentParams>;
template void BundleAdjustmentParams::fields(const BundleAdjustmentParams&, const FieldDescriber&);

}  // namespace reftrack
