#pragma once
// WideBaselineParams: matching the current frame to a reference image through the chained
// homography and local affine maps, scored by the warped correlation of Eq. 19 (paper Sec. 6.2).
#include <opencv2/core.hpp>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct WideBaselineParams : ParamSection<WideBaselineParams> {
  static constexpr const char* kSection = "wide_baseline";

  int dx = 10;  // candidates within a (2dx+1) x (2dy+1) window around p'_A
  int dy = 10;
  int halfWindow = 5;        // n: the warped correlation compares (2n+1)^2 pixels
  double minScore = 0.7;     // keep the best candidate only above this warped NCC
  int affineNeighbours = 3;  // previous-frame matches defining the local affine map L
  // At most this many reference corners (at 320x240, times countScale: ResolutionScale.hpp) are
  // tried per reference and frame, those with a 3D point first, spread over the image; 0 = all.
  int referenceCornersAt320x240 = 50;
  int referenceCornersFor(cv::Size imageSize) const;  // 0 = all
  // Step 1, the frame-to-frame homography H, only predicts: it matches the strongest this many
  // corners of each frame (at 320x240, times countScale).
  int frameToFrameCornersAt320x240 = 40;
  int frameToFrameCornersFor(cv::Size imageSize) const;
  // The 6-DOF frames keep corners down to this fraction of the strongest Harris response when
  // corners.quality is stricter (the response grows with contrast^4: 1e-4 is a tenth of the
  // strongest corner's contrast). Real hand-held video of a card on a bare table: 0.01 finds
  // ~28 corners per 640x480 frame and tracks 86 of 161 frames, 1e-4 tracks all 161.
  double frameCornerQuality = 1e-4;
  // A frame started from a given pose (PoseTracker::seed: a hand-over between reference pairs or
  // a relocalisation candidate) has no frame-to-frame step; its candidates are searched within
  // +-seedSearch pixels (at 320x240, scaled) of the map points' projections, which absorbs a
  // seed a few centimetres or degrees off (at 1 m and 640x480, 1 degree ~ 9 px).
  int seedSearchAt320x240 = 30;
  // Frame-side sub-pixel alignment (PatchAligner): each match's warped reference window is
  // aligned to the frame by Lucas-Kanade, so the measurement is where the reference's measured
  // point lies rather than the independently detected frame corner. Measured on the real desk
  // clip (README "Frame-side alignment"): no gain in accuracy there, so it is off by default.
  bool alignFrameSide = false;
  int alignHalfWindow = 7;  // the alignment's windows are (2n+1)^2 pixels
  // Keypoint measurements (KeypointMeasurer, issue 33): up to this many alignments per frame (at
  // 320x240, times countScale) of the map's keypoint-layer points, projected with the frame's
  // robust linear pose and aligned to the frame by Lucas-Kanade in (2 keypoint_half_window + 1)^2
  // windows, join the three-view terms; 0: none. Each term's SD is the alignment's own, at least
  // keypointSigmaPx, and its point's triangulation covariance (pose.map_point_sd_scale) is
  // computed with that SD at both references. The pose's support is judged on the corners' terms
  // alone (PoseTracker 8c). Measured on the real-clip suite (app/research/README.md, "The
  // keypoint layer's terms by default"), in order / shuffled, mean px: ViSP 0.467 / 0.497 ->
  // 0.384 / 0.377 (p95 1.41 -> 0.92, true / predicted 1.67 -> 1.01), desk 0.348 -> 0.321, shelf
  // 0.179 -> 0.174, the Kinect segments as many frames within 5 px; 40: ViSP 0.417 / 0.405, 150:
  // 0.394 / 0.388. It costs the desk ~0.8 ms per frame (2.5 -> 3.3).
  int keypointPointsAt320x240 = 75;
  int keypointPointsFor(cv::Size imageSize) const;  // 0 = none
  double keypointSigmaPx = 0.3;
  int keypointHalfWindow = 4;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<WideBaselineParams>;  // defined in WideBaselineParams.cpp

}  // namespace reftrack
