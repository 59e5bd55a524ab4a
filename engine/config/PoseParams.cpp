#include "engine/config/PoseParams.hpp"

#include "engine/config/ParamFields.hpp"
#include "engine/core/Error.hpp"

namespace reftrack {

std::string toString(PoseEstimatorKind kind) {
  return kind == PoseEstimatorKind::Standard ? "standard" : "regularised";
}

PoseEstimatorKind parsePoseEstimatorKind(const std::string& text) {
  if (text == "standard") return PoseEstimatorKind::Standard;
  if (text == "regularised" || text == "regularized") return PoseEstimatorKind::Regularised;
  throw Error("parameter 'pose.estimator' must be 'standard' or 'regularised', got '" + text + "'");
}

template <class Self, class Field>
void PoseParams::fields(Self& p, const Field& field) {
  field("estimator", p.estimator, TextForm<PoseEstimatorKind>{toString, parsePoseEstimatorKind});
  field("alpha", p.alpha, Range{0.0, 1e12});
  field("ar_order", p.arOrder, Range{1, 10});
  field("translation_sigma", p.translationSigma, Range{1e-12, 1e6});
  field("rotation_sigma", p.rotationSigma, Range{1e-12, 1e3});
  field("motion_model_file", p.motionModelFile);
  field("rolling_shutter_readout", p.rollingShutterReadout, Range{0.0, 1.0});
  field("estimate_rolling_shutter", p.estimateRollingShutter);
  field("map_point_sd_scale", p.mapPointSdScale, Range{0.0, 100.0});
  field("reliability_prior_observations", p.reliabilityPriorObservations, Range{0.0, 1e6});
  field("verify_min_points", p.verifyMinPoints, Range{0, 100000});
  field("verify_min_share", p.verifyMinShare, Range{0.0, 1.0});
  field("verify_unsure_points", p.verifyUnsurePoints, Range{0, 100000});
  field("verify_unsure_share", p.verifyUnsureShare, Range{0.0, 1.0});
  field("predicted_error_scale", p.predictedErrorScale, Range{1e-6, 1e6});
  field("max_predicted_error_px", p.maxPredictedErrorPx, Range{0.0, 1e6});
}

template struct ParamSection<PoseParams>;

}  // namespace reftrack
