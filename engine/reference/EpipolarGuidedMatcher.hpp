#pragma once
// EpipolarGuidedMatcher: matches the corners of the two reference images V_A <-> V_B when their
// relative pose T_AB is known (paper Sec. 3.3, SPEC §1.2-1.3). A corner of B is a candidate for a
// corner of A when it lies within maxEpipolarDistancePx of A's epipolar line (F from K and T_AB,
// on undistorted coordinates) and its linear triangulation (Eq. 9) lies inside the depth range.
// The references are a wide baseline apart, so B's window is warped (as in Eq. 19) by the
// homography of a local plane through the triangulated point — fronto-parallel, the world's z = 0
// plane (the marker's) and a ring of slanted planes — and the best of these NCCs scores the pair.
// The best score above minScore wins and only mutual best pairs survive (symmetric check); a
// pair is dropped as ambiguous when a runner-up of either corner scores within minScoreMargin,
// and when the correlation peak around B's corner lies more than maxPeakOffsetPx from it;
// each survivor is triangulated (Eq. 9, refined by Eq. 10) from A's corner and that sub-pixel
// peak, and dropped when behind a camera,
// outside the depth range, with too little parallax or with a large reprojection error, and
// when A's window correlates clearly better elsewhere on B's epipolar line (a look-alike matched
// where B's detector missed the true corner).
// Given poses may disagree with the images by more than the gates allow (a depth camera's poses
// given for the colour camera: 1-10 px): a probe in a wider band first fits the images' own
// relative pose to its unambiguous pairs (EpipolarPoseFit); when the given poses measurably
// disagree with it, the gates above are applied in the fitted geometry and each point is then
// triangulated with the given poses, so the map stays in the caller's world.
#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "engine/config/ParamSection.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/EpipolarPoseFit.hpp"
#include "engine/reference/ReferenceMap.hpp"

namespace reftrack {

struct EpipolarMatcherParams : ParamSection<EpipolarMatcherParams> {
  static constexpr const char* kSection = "matching";

  int halfWindow = 7;     // NCC windows are (2n+1)^2 pixels of the full image
  double minScore = 0.8;  // keep the best candidate only above this NCC
  // ... and only when it beats every other candidate of either corner by this much.
  double minScoreMargin = 0.05;
  // The NCC peak around B's corner must lie within this distance of it (pixels). Real video
  // needs the room (hand-held postcard clip: 0.5 px keeps 28 matches and tracks 30% of the
  // frames, 1.5 px keeps 49 and tracks 98%); the simulator's map is as accurate either way.
  double maxPeakOffsetPx = 1.5;
  // Plane hypotheses of the warped window: slantAzimuths planes tilted by slantDeg from
  // fronto-parallel (0 azimuths: fronto-parallel and the world plane only).
  int slantAzimuths = 6;
  double slantDeg = 50.0;
  double maxEpipolarDistancePx = 2.0;  // candidate's distance to the epipolar line (pixels)
  double minDepthMetres = 0.05;        // depth range (camera A's z) of admissible points
  double maxDepthMetres = 50.0;
  double minParallaxDeg = 1.0;          // angle between the two viewing rays
  double maxReprojectionErrorPx = 1.0;  // after Eq. 10, in either image
  // A's window is also correlated along B's whole epipolar line (depth range, 1 px steps, the
  // match's plane hypothesis): a match is dropped when another peak of that profile, more than
  // kLineRivalClearancePx away, scores at least this much above the match's own score: a clearly
  // better place where B's detector found no corner (an AprilTag board's look-alike corners). 2:
  // no check. Measured on the real-clip suite: 0.1-0.2 give the same maps and poses; ViSP refs
  // 0/40 in order 0.518 -> 0.467 px, desk, shelf and Kinect unchanged; 0 or -0.05 (near-equal
  // rivals too) change the Kinect maps and their far frames' poses.
  double lineRivalLead = 0.1;
  // The probe of the given poses: pairs up to this far from A's line (pixels; 0 or not above
  // max_epipolar_distance_px: no probe) are scored too; their unambiguous mutual best pairs fit
  // the images' own relative pose (EpipolarPoseFit). The given poses disagree with the images
  // when those pairs' median distance to the given lines exceeds pose_disagreement_px and
  // pose_disagreement_ratio times their median under the fitted pose; then the gates above are
  // applied in the fitted geometry (the map keeps the points of the given poses). Measured
  // (`experiment-reference-pair`): Kinect frames 200/220 (depth-camera poses for the colour
  // camera): SIFT matches 2.42 px median from the given lines, 0.40 from the fitted ones; 40 cm
  // pairs 5-10 px; the sharp clips' given poses fit better than the fitted ones (0.2 px).
  double probeEpipolarDistancePx = 12.0;
  double poseDisagreementPx = 0.5;
  double poseDisagreementRatio = 2.0;

  template <class Self, class Field>  // its keys, in order: ParamFields.hpp
  static void fields(Self& self, const Field& field);
};
extern template struct ParamSection<EpipolarMatcherParams>;  // EpipolarGuidedMatcher.cpp

// What happened to the corners, for the `prepare` summary.
struct EpipolarMatchStats {
  int cornersA = 0, cornersB = 0;
  int candidatePairs = 0;     // (A, B) pairs passing the epipolar and depth gates
  int mutualMatches = 0;      // mutual best pairs above minScore: the candidate matches
  int droppedAmbiguous = 0;   // a runner-up scores within minScoreMargin of the best
  int droppedLineRival = 0;   // a peak along B's epipolar line lineRivalLead above the match's
  int droppedPeakOffset = 0;  // correlation peak more than maxPeakOffsetPx from B's corner
  int droppedBehindCamera = 0;
  int droppedOutsideDepthRange = 0;
  int droppedLowParallax = 0;
  int droppedReprojection = 0;
  int kept = 0;
  // RMS over both images of the kept matches (against A's corner and B's correlation peak),
  // under the given poses.
  double reprojectionRmsPx = 0.0;
  // The probe (matching.probe_epipolar_distance_px): its unambiguous mutual pairs, the relative
  // pose they fit (when there were enough) and whether the given poses disagree with it.
  int probeMatches = 0;
  std::optional<EpipolarPoseFit> poseFit;
  bool posesDisagree = false;
};

struct EpipolarMatchResult {
  // Kept matches, 3D point in camera A's frame; peakB: the correlation peak in B it was
  // triangulated from (peakA none: A's corner).
  std::vector<ReferenceMatch> matches;
  std::vector<float> scores;  // NCC of each kept match
  EpipolarMatchStats stats;
};

class EpipolarGuidedMatcher {
 public:
  using Params = EpipolarMatcherParams;
  // The probe fits a relative pose only from at least this many pairs (and decides only when at
  // least this many fit it): fewer cannot tell a pose error from a few wrong pairs.
  static constexpr int kMinProbeMatches = 12;
  // A rival peak on the epipolar line must lie farther than this from the match (pixels).
  static constexpr double kLineRivalClearancePx = 2.0;

  // T_A, T_B: world->camera poses of the references (T_AB = T_B * T_A^-1 maps camera-A points
  // to camera B). Throws reftrack::Error on bad params or a baseline too short to define
  // epipolar lines.
  EpipolarGuidedMatcher(PinholeCamera camera, const RigidPose& T_A, const RigidPose& T_B,
                        Params params = {});

  // grayA/grayB: CV_8UC1 reference images; corners as detected (with lens distortion).
  EpipolarMatchResult match(const cv::Mat& grayA, const std::vector<cv::Point2f>& cornersA,
                            const cv::Mat& grayB, const std::vector<cv::Point2f>& cornersB) const;

  // Fundamental matrix on undistorted pixels: ~p_B^T F ~p_A = 0 (SPEC §2).
  const Eigen::Matrix3d& fundamental() const { return F_; }
  // Perpendicular distance (pixels) of undistorted pB to the epipolar line of undistorted pA.
  double epipolarDistance(const Eigen::Vector2d& pA, const Eigen::Vector2d& pB) const;

 private:
  // Local linear map (window offsets in A -> offsets in B) at undistorted pA for plane hypothesis
  // `plane` through the point P (camera A's frame); nullopt when that plane is seen almost edge-on.
  std::optional<cv::Matx22f> localMapAtoB(const Eigen::Vector2d& pA, const Eigen::Vector3d& P,
                                          std::size_t plane) const;

  PinholeCamera camera_;
  RigidPose T_AB_;
  Params params_;
  Eigen::Matrix3d F_;
  Eigen::Matrix3d Kinv_;  // K^-1, for every plane hypothesis and epipolar-line sample
  std::vector<Eigen::Vector3d> planeNormalsA_;  // unit normals of the plane hypotheses, frame A
};

}  // namespace reftrack
