#pragma once
// HomographyTrackerParams: registration of each frame to a stored reference frame (paper Sec. 7.3,
// SPEC §5). The guided search window is given at 320x240 and scales with the image.
#include <opencv2/core.hpp>
#include <string>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

// The viewpoint-invariant keypoint layer of cold registration (OpenCV features2d detectors).
enum class KeypointLayer { None, Orb, Akaze, Sift };
std::string keypointLayerName(KeypointLayer layer);  // "none", "orb", "akaze", "sift"
// Parses those names; throws reftrack::Error listing them on anything else.
KeypointLayer parseKeypointLayer(const std::string& name);

struct HomographyTrackerParams : ParamSection<HomographyTrackerParams> {
  static constexpr const char* kSection = "homography";

  // Matches are searched within +-this of the predicted position (pixels at 320x240).
  double guidedSearchHalfSizePx = 8.0;
  // Predict with the frame-to-frame homography chained with the last frame-to-reference one
  // (otherwise the last frame-to-reference homography alone is the prediction).
  bool frameToFramePrediction = true;
  // While lost, match every reference corner against the whole frame (else: within the
  // correlation search window around the same position).
  bool reacquireWholeImage = true;
  // While lost, the frame and the reference are matched with this many times the corner count:
  // a frame that barely overlaps the reference (a wide pan) then still shares enough corners
  // with it to be registered. 1: the tracking corner count. Above 320x240 the re-acquisition
  // count stays that of 320x240 (unguided matching costs the square of the count).
  double reacquireCornerFactor = 8.0;
  // The re-acquisition corners also go down to this fraction of the strongest Harris response
  // and this close to each other (pixels at 320x240): the sliver a wide pan shares with the
  // reference (30 degrees of a 33 degree view: ~30 px) must hold enough corners on both sides.
  // Measured on the rotation sweep's frames at 30 degrees: with 3x the corners at 0.01 / 8 px
  // (the tracking corners' values) 1-7 correct unguided matches per trial (6 trials); with 8x at
  // 1e-4 / 4 px at least 13 in each of 100 trials.
  double reacquireCornerQuality = 1e-4;
  double reacquireMinDistancePx = 4.0;
  // While tracking, each frame is searched with this many times the reference's corner count:
  // two independent selections of the strongest few corners share only part of their corners
  // (measured at 320x240 with 55 on both sides: 31 of 52 visible reference corners matched
  // 2 degrees into a pan), and a denser frame set gives most visible reference corners a
  // counterpart inside the guided search window. 1: the same count on both sides.
  double frameCornerFactor = 2.0;
  // With a calibrated camera (K given to the tracker), a frame the 8-parameter homography does
  // not register is tried once more with the rotation-only model H = K R K^-1 (3 parameters),
  // under the same inlier rules: a frame that shares only a sliver with the reference (a wide
  // pan) pins a general homography down along the sliver only.
  bool rotationModel = true;
  // Cold registration (the first frame, and whenever the tracker would match unguided): the
  // reference's keypoints (detected once) are matched to the frame's by descriptor, a robust
  // homography fitted to them is the prediction around which the reference corners are matched
  // with warped correlation windows, and that guided fit (under the usual inlier rules) is the
  // result. Registers views far from the reference (out-of-plane rotation to ~50 degrees, scale
  // 0.5-2, any in-plane rotation) that square correlation windows cannot. none: unguided
  // correlation matching only. When the keypoint layer fails, unguided matching still runs.
  // ORB: measured at 640x480, one thread, on 180 views of four Oxford img1 (tilt 0-60 degrees,
  // scale 0.5-2, three in-plane rotations) registered within 1 px at the frame corners: ORB
  // 164, AKAZE 163, SIFT 169 (SIFT on the half-size frame 162), with ORB's cold frames 3-4x
  // faster than SIFT's and AKAZE's in the same run.
  KeypointLayer keypoints = KeypointLayer::Orb;
  int keypointFeatures = 1000;  // keypoints kept per image (the strongest)
  // Lowe's ratio test: a match is kept when its descriptor distance is below this fraction of
  // the second-nearest one (and it is the mutual nearest neighbour).
  double keypointRatio = 0.8;
  // The frame is searched for keypoints at this fraction of its resolution (1: full).
  double keypointDetectScale = 1.0;
  // Inlier threshold of the keypoint homography (pixels at 320x240): it only has to bring the
  // correlation windows within the guided search range.
  double keypointInlierThresholdPx = 1.5;
  // Around the keypoint homography, each reference window (warped by it) is searched at every
  // pixel within +-this (pixels at 320x240) of its predicted position: the frame's own corners
  // do not repeat the reference's under a strong change of scale or viewpoint.
  double keypointSearchHalfSizePx = 3.0;
  // Every registered H (tracked in order or cold) is finally refined by HomographyRefiner: the
  // reference warped by H is aligned to the frame at refinePoints textured reference points
  // (per 320x240, scaled with the image) by Lucas-Kanade, and H re-fitted to them with Cauchy
  // weights until it stops moving. The result no longer depends on how the frame was
  // registered (measured on the shared planar clips, cold vs in-order at the frame corners:
  // up to 16 px without it, <= 0.6 px with it). 0: off.
  int refinePoints = 150;
  // Cold registration from steep views (ASIFT-like, Morel & Yu 2009): the reference's keypoints
  // are also detected on this many synthetic views of it tilted by 50 degrees (compressed by
  // cos 50 across directions spread over 180 degrees), their positions mapped back to the
  // reference. They are matched only when the plain reference's keypoints give no homography
  // with keypointConfidentInliers inliers. 0: off.
  int keypointTiltViews = 4;
  // A second ring of synthetic views tilted by keypointSteepTiltDeg (ASIFT's tilt 2 is 60
  // degrees), for views of 55-70 degrees. 0: off.
  int keypointSteepTiltViews = 5;
  double keypointSteepTiltDeg = 65.0;
  int keypointConfidentInliers = 20;
  // Without a confident homography, the views are matched once more one-to-one — mutual nearest
  // neighbours without the ratio test, which a repeated pattern (bricks, tiles) fails at its true
  // matches — and fitted with MAGSAC++ (cv::USAC_MAGSAC).
  bool keypointOneToOne = true;
  // The check every cold registration must pass before it is reported (RegistrationVerifier):
  // textured reference points on a grid, their windows warped by H, are correlated with the
  // frame within +-verifySearchPx of their mapped position (pixels at 320x240, on the pyramid
  // levels where the two images have about the same scale; peaks with NCC >= verifyMinScore),
  // and a homography correction is fitted to the peaks (inlier distance verifyTolerancePx). H
  // passes when at least verifyMinFraction of the points the frame can measure confirm the
  // correction, the confirming points cover at least verifyMinSpread of the 3 x 3 grid over the
  // overlap, and the correction moves no point of the textured part of the overlap by more than
  // verifyMaxOffsetPx. Measured (`experiment-homography --experiment verify`, real and hard
  // pairs): no homography 10 or 20 px off at the frame corners passes, 71 of 180 5 px off, 162
  // of 180 3 px off; the true ones pass except where the images contradict them (trees, bikes
  // 1->6). With 1.5 a correct cold registration of a shared clip's frame was refused.
  // false: no check.
  bool verify = true;
  double verifyMinScore = 0.5;
  double verifySearchPx = 4.0;
  double verifyTolerancePx = 1.0;
  double verifyMinFraction = 0.3;
  double verifyMinSpread = 0.5;
  double verifyMaxOffsetPx = 2.0;
  // The check judges H where it is known to hold: the convex hull of its inlier matches (plus a
  // margin), which must cover at least this fraction of the overlap (on a partly planar view the
  // trees, people, sky and other facades do not follow the plane's H and are not compared).
  double verifyMinSupport = 0.15;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<HomographyTrackerParams>;  // defined in
                                                               // HomographyTrackerParams.cpp

}  // namespace reftrack
