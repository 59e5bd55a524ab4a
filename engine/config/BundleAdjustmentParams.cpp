#include "engine/config/BundleAdjustmentParams.hpp"

#include "engine/config/ParamFields.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

namespace {

// The rule of bundle_adjustment.loss (ParamFields.hpp).
struct KnownLoss {
  void check(const std::string& name, const std::string& loss) const {
    if (loss != "huber" && loss != "cauchy" && loss != "none")
      throw Error("parameter '" + name + "' must be cauchy, huber or none, got '" + loss + "'");
  }
};

}  // namespace

template <class Self, class Field>
void BundleAdjustmentParams::fields(Self& p, const Field& field) {
  field("loss", p.loss, KnownLoss{});
  field("loss_scale_px", p.lossScalePx, Range{1e-3, 1000.0});
  field("outlier_threshold_px", p.outlierThresholdPx, Range{1e-3, 1000.0});
  field("max_iterations", p.maxIterations, Range{1, 100000});
  field("min_determined_points", p.minDeterminedPoints, Range{3, 1000000});
}

template struct ParamSection<BundleAdjustmentParams>;

}  // namespace reftrack
