#pragma once
// RelocalisationParams (YAML section `relocalisation`): the keypoint layer stored in the map and
// the cold start / relocalisation of the 6-DOF tracker from any view (issue 13). Keypoint counts
// are given at 640x480 and scale with the image area; pixel figures are given at 320x240 and
// scale with resolutionScale().
#include <opencv2/core.hpp>
#include <string>

#include "engine/config/ParamSection.hpp"

namespace reftrack {

struct RelocalisationParams : ParamSection<RelocalisationParams> {
  static constexpr const char* kSection = "relocalisation";

  bool enabled = true;  // false: start and re-start only near a reference (paper)
  // Detector + descriptor: orb | akaze | sift. On the synthetic scene of issue 13 all three
  // relocalise every view without a wrong pose (median CPU per attempt ORB 19 ms, AKAZE 139 ms,
  // SIFT 285 ms). Real footage decides the default (README "Cold starts"): the shared desk clip
  // with every frame a cold start, references 0 and 40 — ORB 280 of 400 frames posed, SIFT 357,
  // AKAZE fewer and with more candidates refused by the verification; ORB's far views (13-19 cm
  // and 15-27 degrees from both references) found 9-11 inliers among ~570 matches.
  std::string keypoints = "sift";
  // Keypoints detected in a frame (640x480). Measured on 200 random views of 8 walkaround
  // references (experiment-relocalisation): 1000 pose 87.5% of them, 1500 92.5%, 2000 92.5%, no
  // wrong pose in each case; the first frame's median cost 21.5, 22.5, 26.4 ms.
  int featuresPerFrame = 1500;
  // ORB only: when a frame gives no pose, it is detected again with this many pyramid levels
  // above the image (upsampled 1.2x each; the keypoint cap grows by a quarter per level) and
  // matched to every reference: a far view's scene is small. 0: no second detection.
  int frameFinerLevels = 3;
  // SIFT only: a frame is reduced by this factor before detection (cv::INTER_AREA; keypoints are
  // mapped back to frame pixels). OpenCV's SIFT doubles the image for its first octave, which
  // costs most of an attempt. Real desk clip, references 0/40, every frame a cold start (`track
  // --cold-starts`; 151 relocalisation attempts, one thread): scale 1.0: 388 of 400 frames posed,
  // 140 attempts verified, median 98 ms per attempt (detection 81 ms CPU); 0.7: 393, 144, 43 ms
  // (detection 29 ms); 0.6: 369, 121, 36 ms; 0.5: 375, 126, 28 ms. The references keep full
  // resolution (matching across scales is what SIFT is for).
  double siftFrameScale = 0.7;
  int featuresPerReference = 2000;  // keypoints stored per reference (640x480)
  // ORB only: pyramid levels above each reference image (upsampled 1.2x each) at prepare time,
  // for views closer than the reference's. Measured on the first 93 of the 200 views of
  // experiment-relocalisation (8 references, seed 1): 3 levels relocalised 88/93 vs 86/93 with
  // none (all three views at 0.5-0.6x the distance that none left without a pose), none wrong.
  int referenceFinerLevels = 3;
  double ratio = 0.8;  // Lowe's ratio test on the two nearest descriptors
  // Retrieval: match only the best-voted references. Measured on 8 references of a synthetic
  // room corner (12 views, one thread): all 8 22 ms CPU per attempt, 4 18.8, 2 15.9, every view
  // relocalised in each case.
  int referencesToMatch = 2;
  int ransacIterations = 300;    // PnP-RANSAC
  double reprojectionPx = 2.0;   // PnP-RANSAC inlier threshold (pixels at 320x240)
  int minInliers = 20;           // fewer inliers: no candidate (never a pose without support)
  double minInlierRatio = 0.25;  // inliers / 2D-3D matches below this: no candidate
  int attemptEveryFrames = 1;    // while lost, try at most on every n-th frame
  // The time budget while lost (RelocalisationBudget): the recovery (re-seed, start near a
  // reference, relocalisation) spends at most budget_burst_ms plus budget_ms_per_frame per lost
  // frame; a frame the budget leaves out is not searched, and a blank frame (a covered lens)
  // costs nothing. Recorded input is charged the modelled cost of the work (RecoveryWork: CPU
  // milliseconds of one core of the development machine, the same on any machine and load), a
  // live camera the process CPU time as measured (MultiReferenceTracker::setBudgetClock). At 30
  // fps 3.0 ms per frame is 9% of one core; the burst lets the first ~4 searches (45-50 ms each)
  // come on consecutive frames: a cut, a short look away. Tracking again refills it. `bench-real
  // --order away:900 --away-input` (the other shared clip as the other scene): desk 3.26 ms per
  // frame while away (9.8% of a core), back 1 frame after the return; shelf 3.31 ms (9.9%), back
  // after 15 frames (one search's cost over the rate: the longest wait). Without a budget: 8.1 ms
  // (24%).
  double budgetMsPerFrame = 3.0;
  double budgetBurstMs = 200.0;
  // While lost, a frame whose small blurred image correlates with a reference's at least this
  // much (SceneResemblance, 40 px wide, shifts of +-2 px) looks like the scene: it may spend the
  // part of the burst kept for such frames (budget_reserve_share of it), so the search runs when
  // the scene comes back instead of when the budget next allows (`bench-real --order away:900`:
  // back after 6 and 7 frames with no reserve, 0 with no budget at all). Measured on the shared
  // clips (tests SceneResemblanceRealFootage.*): every frame of a clip against its two references
  // 0.60-1.0 (desk 0/40; shelf 0/60 0.77-1.0, ViSP 0/40 0.91-1.0, Kinect 0/40 frames 0-70
  // 0.72-1.0); another scene's frames at most 0.29 (desk frames against the shelf's references),
  // the Kinect kitchen away from its table (frames 110-170) at most 0.15. 0: no reserve, no
  // resemblance asked.
  double resemblanceMinScore = 0.5;
  double budgetReserveShare = 0.5;
  // The inliers must cover at least this many cells of a 4x4 grid over the frame: a pose held
  // up by one small patch of the image is too weakly constrained to hand to the tracker.
  int minInlierCells = 3;
  // The pose's standard deviations predicted from the inliers (Gauss-Newton covariance of the
  // reprojection residuals) must stay below these: rotation (degrees) and position (fraction of
  // the median inlier depth). A distant patch of the scene pins a pose down poorly however many
  // inliers it has. Measured on the synthetic corner: accepted views 0.07-0.46 degrees,
  // 0.04-0.20%; the one pose off by 3.4 degrees and 18 cm (the corner 2.6 m away, in 3 of 16
  // grid cells) predicted 0.69 degrees, 0.31% — the prediction is ~5x optimistic, the map
  // points' errors being correlated, so the bounds are tight.
  double maxRotationSigmaDeg = 0.5;
  double maxPositionSigmaRatio = 0.0025;
  // Every start (near a reference, or from a relocalisation candidate) is confirmed on its frame
  // by the wide-baseline matching of every map point from its pose, and reported only when at
  // least this many of the confirmed matches are to distinctive reference corners
  // (DistinctiveCorners: no look-alike within reach of the search). A pose one period off on
  // repeated texture (a chessboard) keeps its matches on the texture and loses the rest. Real desk
  // clip, references 0 and 40, every frame a cold start (README "Cold starts"): wrong starts had
  // at most 5, right ones a median of 22 and 95% at least 6 ...
  int minDistinctiveInliers = 8;
  // ... and, when the map has a keypoint layer, at least this many of the frame's ratio-test
  // keypoint matches (no look-alike in the references), and this share of them, must agree with
  // the pose within reprojection_px; a relocalisation candidate whose confirmed pose keeps
  // min_inliers of its own ratio-test inliers is verified by them alone. Real desk clip, every
  // frame a cold start, references 0/40, 200/240, 100/140 and 300/340: six starts two squares off
  // (93 px, refs 200/240) had 13-18 distinctive corners but 4-10 agreeing keypoints, 3-7% of
  // their matches; right starts had at least 16 and 22% with the three layers of 164-408 points,
  // and 8-10 (6-7%) for four of 216 with the 74-point layer of refs 100/140 (refused: a sparse
  // layer lets false matches through its ratio test). Relocalised views seeing mostly the
  // chessboard had 5-7 distinctive corners but 25-50 kept inliers. 0, 0: no keypoint check.
  int minKeypointSupport = 12;
  double minKeypointAgreement = 0.10;
  // Keypoint layer (preparation): a keypoint gets a 3D point from a match with another view when
  // the match lies this close to its epipolar line and the triangulated point reprojects this
  // close in both views (pixels at 320x240), in front of both cameras, ...
  double triangulationPx = 1.0;
  // ... and the two rays meet at least at this angle (degrees): smaller parallax, no point.
  double minParallaxDeg = 1.0;

  // Keypoint counts for an image of `size` (the 640x480 figures scaled with the area).
  int featuresPerFrameFor(cv::Size size) const;
  int featuresPerReferenceFor(cv::Size size) const;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<RelocalisationParams>;  // defined in RelocalisationParams.cpp

}  // namespace reftrack
