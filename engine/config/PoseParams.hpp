#pragma once
// PoseParams: 6-DOF pose estimation (paper Sec. 4-5, SPEC §3): standard least squares (Eq. 12)
// or the temporally regularised criterion (Eq. 13) with an AR(p) motion model.
#include <opencv2/core.hpp>
#include <string>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

enum class PoseEstimatorKind { Standard, Regularised };

// "standard" / "regularised"; parsing throws reftrack::Error listing the accepted names.
std::string toString(PoseEstimatorKind kind);
PoseEstimatorKind parsePoseEstimatorKind(const std::string& text);

struct PoseParams : ParamSection<PoseParams> {
  static constexpr const char* kSection = "pose";

  PoseEstimatorKind estimator = PoseEstimatorKind::Regularised;
  double alpha = 1.0;               // weight of the prior term in Eq. 13
  int arOrder = 1;                  // p of the AR(p) motion model
  double translationSigma = 0.001;  // process noise Q: metres per frame
  double rotationSigma = 0.001;     // process noise Q: radians per frame
  std::string motionModelFile;      // optional fitted model (overrides order and Q); "" = none
  // Rolling shutter: the sensor's readout time (first row to last) as a fraction of the frame
  // interval (a 20 ms readout at 30 fps: 0.6); 0 = global shutter. While tracking, each frame
  // corner is moved back along its frame-to-frame motion to where it was when the middle row was
  // exposed (the instant the pose stands for) before it enters the pose estimation.
  double rollingShutterReadout = 0.0;
  // Estimate the readout online from the tracked frames (RollingShutterEstimator), starting from
  // rolling_shutter_readout; a global-shutter camera's estimate stays at about 0. Off by default
  // (decided on real clips, README "Defaults"): on the shared desk clip (a global shutter) the
  // estimate stays at 0.000 and changes nothing; on a held-out hand-held desk clip it settled at
  // 0.59 and raised the cube error from 0.763 to 0.867 px. The simulator's webcam preset (a known
  // rolling shutter) needs it: `experiment-6dof --effects webcam` turns it on.
  bool estimateRollingShutter = false;
  // The three-view terms count each map point's own uncertainty: the residual's covariance is
  // the frame pixel's sigma^2 I plus the point's covariance from its two-reference triangulation
  // seen from the frame, the references' corners taken this many times as precise (SD) as the
  // corner-variance model says; 0 leaves it out. References a few centimetres apart fix depth
  // poorly, and a frame far from them sees that error magnified; the epipolar terms, which need no
  // depth, then carry more of the pose. Chosen on the real desk clip and the simulator (README
  // "Defaults decided on real footage"), with the learned reliability below on: scale 0 / 0.5 / 1,
  // desk refs 0/40 cube error mean 0.469 / 0.344 / 0.332 px, the other three pairs unchanged
  // (0.323-0.326, 0.229-0.235, 0.275-0.281); simulator webcam preset 0.104 / 0.105 px.
  double mapPointSdScale = 0.5;
  // Learned reliability (MeasurementReliability): each map point's three-view terms and each
  // reference corner's epipolar terms are weighted by what their residuals at the accepted poses
  // have shown, shrunk toward the average source by this many observations; 0 turns it off.
  // Real map points differ in accuracy far more than the corner-variance model says (desk clip,
  // four reference pairs: the quartiles of the points' SD about the true pose average 0.18 to
  // 1.1 px, of their biases 0.15 to 1.4 px; the model says 0.07 for all). Decided on
  // the real desk clip and the simulator (README "Defaults decided on real footage"): cube error
  // mean over four reference pairs 0.386 -> 0.294 px, simulator webcam preset 0.129 -> 0.105 px.
  double reliabilityPriorObservations = 2.0;
  // Learned noise of each kind of measurement (MeasurementGroupNoise): the corner points'
  // three-view terms, the keypoint points' and the epipolar terms to A and to B are weighted
  // against each other by what their residuals at the accepted poses have shown, averaged over
  // about this many tracked frames; 0 turns it off (the corner-variance model's weights alone).
  // The corner model is a sharp, global-shutter camera's (Fig. 7: ~0.1 px); on other cameras each
  // kind is off by its own factor (ViSP's desk camera, true poses: epipolar terms 20-200 times
  // their modelled variance, corner points 5-40, keypoint points 1-5). Measured on every real clip
  // with true poses (app/research/README.md, "One set of defaults for every camera").
  double groupNoiseFrames = 10.0;
  // Outlier gate of the 3D-2D pairs (stage 7): after PnP-RANSAC (whose threshold is the tracker's
  // wide gate), the pairs are gated again at this many times their robust reprojection SD (median
  // residual), at least min_outlier_gate_px (pixels at 320x240, scaled), at most the wide gate,
  // and the linear pose refitted to them, twice; the estimate's terms keep the wide gate. A few
  // wrong matches within the wide gate (ViSP clip: 18-40 px off the true pose, 2-9 px off the
  // estimate) otherwise pull the pose by a pixel or more. 0 turns it off.
  double outlierGateSigmas = 3.0;
  double minOutlierGatePx = 0.5;
  // After the pose is estimated, a term whose whitened residual exceeds this many times its
  // kind's robust SD (median) is dropped and the pose estimated again; 0 (the default) turns it
  // off: at 4 it took the ViSP clip 0.518 -> 0.566 px and helped no clip by more than 0.01 px.
  double rejectSigmas = 0.0;
  // Every pose is checked before it is reported, whatever produced it (PoseVerifier): at the
  // distinctive map points it projects into the frame, the reference windows warped by the pose
  // must correlate with the frame. It needs this many of them confirmed (0 turns the check off)
  // and this share of those it could check; a pose short of that is `lost` with the reason, and
  // the same frame goes on to the start near a reference and the relocaliser.
  int verifyMinPoints = 8;
  double verifyMinShare = 0.2;
  // Short of those but with at least these, the pose is unsure rather than refuted: the
  // relocaliser is asked on the same frame, and the pose is kept when it finds a pose that agrees
  // with it, or finds none and the pose was tracked on from the last frame (not a seed or a jump).
  int verifyUnsurePoints = 4;
  double verifyUnsureShare = 0.12;
  // While a track goes on unbroken, an unsure pose tracked on from the last frame is put to the
  // relocaliser at most every this many frames; between, the last opinion that kept one stands
  // (1: every frame). On the desk clip's far views every frame was unsure: 28 of 400 frames in
  // order asked, 43-60 ms each on the full-size frame (the mean frame 6.95 ms against a median of
  // 2.5); now 5, on the reduced frame, ~36 ms each. Once in 15 frames is 2-3 ms per frame, the
  // rate relocalisation.budget_ms_per_frame allows a lost tracker (10% of a core at 30 fps).
  // Poses that are seeds or follow a jump are always asked: the opinion guards those against
  // look-alikes.
  int verifyUnsureEveryFrames = 15;
  // Predicted overlay error (PredictedOverlayError.hpp): the RMS image displacement of the
  // overlay's points under Omega_k, rescaled a posteriori by the frame's observed residuals
  // (aPosterioriFactor), times this calibration factor. Omega_k alone was 13-25 times too small on
  // the real clips (it assumes the corner model's noise, ~0.1 px, and counts the temporal prior as
  // independent information); rescaled it is right on the simulator's exact map and truth (true /
  // predicted cube error median 1.08, cold starts), and 1.6-2.1 times too small on the real clips:
  // errors every frame and point share there (the map's registration from its references' poses,
  // which the clips' truth gives to ~0.2 px, and that truth's own noise) show in no frame's
  // residuals. Measured by scripts/predicted-error.sh at factor 1, true / predicted median in
  // sequence order: desk refs 0/40 1.72 (100/140 1.62, 200/240 2.02, 300/340 1.58), shelf refs
  // 0/60 2.12 (0/30 1.96, 100/160 0.99); 1.7 is their geometric mean (1.67), rounded: desk 0/40
  // then 1.01, shelf 0/60 1.25 (cold starts: 1.01, 1.35).
  double predictedErrorScale = 1.7;
  // A tracked frame whose predicted overlay error exceeds this (pixels of the frame) is reported
  // `uncertain` with the reason: the pose is still given and the tracker goes on from it, but it
  // is not drawn as if exact. 0 turns the check off. Chosen on the real clips (752x480): the
  // largest prediction of a correctly tracked frame was 1.01 px in sequence order over the seven
  // reference pairs above (1.25 px over their cold starts), while on the desk clip with frames
  // 100-199 masked but for their left quarter the two poses 5.6 and 7.8 px off were predicted
  // 2.5 px off (and the frames 2-4 px off 2-4 px): 2 px flags those and no correct frame.
  double maxPredictedErrorPx = 2.0;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<PoseParams>;  // defined in PoseParams.cpp

}  // namespace reftrack
