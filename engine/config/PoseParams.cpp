#include "engine/config/PoseParams.hpp"

#include "engine/config/FieldDescriber.hpp"
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
  field("estimator", p.estimator, TextForm<PoseEstimatorKind>{toString, parsePoseEstimatorKind})
      .help(
          "regularised: least squares with the motion model's prior (Eq. 13); standard: without "
          "(Eq. 12)");
  field("alpha", p.alpha, Range{0.0, 1e12})
      .help(
          "Weight of the motion prior (regularised); larger: smoother poses, slower to follow "
          "motion");
  field("ar_order", p.arOrder, Range{1, 10}).help("Order p of the AR(p) motion model");
  field("translation_sigma", p.translationSigma, Range{1e-12, 1e6})
      .help(
          "Motion model noise in metres per frame; larger: faster motion expected, less smoothing");
  field("rotation_sigma", p.rotationSigma, Range{1e-12, 1e3})
      .help(
          "Motion model noise in radians per frame; larger: faster turns expected, less smoothing");
  field("motion_model_file", p.motionModelFile)
      .help(
          "A fitted motion model (`reftrack fit-motion`) replacing ar_order and the sigmas; \"\": "
          "none");
  field("rolling_shutter_readout", p.rollingShutterReadout, Range{0.0, 1.0})
      .help(
          "Sensor readout time as a fraction of the frame interval (20 ms at 30 fps: 0.6); 0: "
          "global shutter");
  field("estimate_rolling_shutter", p.estimateRollingShutter)
      .help("Estimate the readout online from the tracked frames, from rolling_shutter_readout on");
  field("map_point_sd_scale", p.mapPointSdScale, Range{0.0, 100.0})
      .help(
          "Weigh map points by their triangulation uncertainty, corner SD scaled by this; 0: off");
  field("reliability_prior_observations", p.reliabilityPriorObservations, Range{0.0, 1e6})
      .help(
          "Weigh points by their past residuals, shrunk toward the average by this many "
          "observations; 0: off");
  field("group_noise_frames", p.groupNoiseFrames, Range{0.0, 1e6})
      .help(
          "Weigh corner, keypoint and epipolar terms by their kinds' residuals over about this "
          "many frames; 0: off");
  field("outlier_gate_sigmas", p.outlierGateSigmas, Range{0.0, 100.0})
      .help(
          "Re-gate the PnP inliers at this many robust SDs of their residuals, refitting; 0: off "
          "(the wide gate only)");
  field("min_outlier_gate_px", p.minOutlierGatePx, Range{0.0, 1000.0})
      .help("The re-gated outlier gate is never tighter than this (pixels at 320x240, scaled)");
  field("reject_sigmas", p.rejectSigmas, Range{0.0, 1000.0})
      .help(
          "Drop terms beyond this many robust SDs of their kind at the estimate and estimate "
          "again; 0: off");
  field("verify_min_points", p.verifyMinPoints, Range{0, 100000})
      .help(
          "A pose is reported only when this many distinctive map points confirm it by "
          "correlation; 0: no check");
  field("verify_min_share", p.verifyMinShare, Range{0.0, 1.0})
      .help("A pose also needs this share of the map points it could check confirmed");
  field("verify_unsure_points", p.verifyUnsurePoints, Range{0, 100000})
      .help(
          "Short of verify_min_points but with this many, a pose is unsure (relocaliser asked), "
          "not lost");
  field("verify_unsure_share", p.verifyUnsureShare, Range{0.0, 1.0})
      .help("The share of checked points an unsure pose needs (see verify_unsure_points)");
  field("verify_unsure_every_frames", p.verifyUnsureEveryFrames, Range{1, 100000})
      .help(
          "An unsure pose tracked on asks the relocaliser at most every n-th frame of a track; "
          "1: every frame");
  field("predicted_error_scale", p.predictedErrorScale, Range{1e-6, 1e6})
      .help("Calibration factor of the predicted overlay error (measured on real clips)");
  field("max_predicted_error_px", p.maxPredictedErrorPx, Range{0.0, 1e6})
      .help(
          "Frames whose predicted overlay error exceeds this are reported uncertain (frame "
          "pixels); 0: off");
}

template struct ParamSection<PoseParams>;
template void PoseParams::fields(const PoseParams&, const FieldDescriber&);

}  // namespace reftrack
