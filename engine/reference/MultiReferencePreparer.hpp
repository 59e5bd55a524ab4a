#pragma once
// MultiReferencePreparer (issue 13): the offline preparation of paper Sec. 2/3.3 for N >= 2
// reference images. Each reference is posed by the marker (detected in it) or by given poses;
// its corners are found once; every pair whose optical axes differ by at most
// maxPairViewAngleDeg and whose centres lie at least minBaselineMetres apart is matched and
// triangulated exactly as the two-reference preparation does (EpipolarGuidedMatcher: epipolar
// gates, warped NCC, Eq. 9/10). The pairwise matches are merged into multi-view points by
// union-find over (reference, corner); a track holding two corners of one reference is
// inconsistent and dropped. A point seen by two references keeps its pairwise triangulation; one
// seen by 3+ is re-triangulated from all its measurements (its first reference's corner and the
// correlation peaks the pairs found for it elsewhere; linear DLT, then Gauss-Newton on the
// reprojection errors with Ceres) and loses, worst first, every observation reprojecting farther
// than maxTrackReprojectionErrorPx. A map of fewer than targetPoints points whose corners repeat
// poorly (denserCornerMaxRepeat) is made again from denser corners
// (ReferencePreparerParams::denserCorners) and the one with more points kept. Last,
// the keypoint layer for relocalisation is built (buildReferenceKeypoints with
// params.relocalisation, unless disabled there). Bad input throws reftrack::Error naming the image
// or pair.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/reference/ReferencePreparer.hpp"

namespace reftrack {

struct ReferencePairReport {
  int a = -1, b = -1;
  double baselineMetres = 0.0;
  double viewAngleDeg = 0.0;  // between the two optical axes
  bool matched = false;       // false: skipped by the gates (reason in `skipped`)
  std::string skipped;
  EpipolarMatchStats matching;
  bool denserCorners = false;  // matched again with ReferencePreparerParams::denserCorners()
  bool merged = false;         // kept matches >= minPairMatches: its matches went into the map
};

struct MultiPreparationReport {
  std::vector<std::optional<double>> markerRmsPx;  // per reference (marker poses only)
  std::vector<int> corners;                        // per reference
  std::vector<ReferencePairReport> pairs;          // every pair a < b, in order
  int tracks = 0;                         // connected (reference, corner) groups of 2+ corners
  int inconsistentTracks = 0;             // dropped: two corners of one reference
  int droppedObservations = 0;            // reprojection error above the threshold after refinement
  int droppedPoints = 0;                  // fewer than two observations left, or behind a camera
  std::vector<int> observationHistogram;  // [k]: points seen by exactly k references
  double multiViewRmsPx = 0.0;  // reprojection RMS of the 3+-view points (their measurements)
  std::optional<ReferencePoseRefinement> poseRefinement;  // when params.refines()
  // The map was short of params.targetPoints with the references' corners: made again from
  // denser ones (denserCorners: the map kept is that one; pointsBeforeDenserCorners: the first
  // map's points; denserCornersGave: the denser map's points when it was not kept, else -1).
  bool denserCorners = false;
  int pointsBeforeDenserCorners = -1;
  int denserCornersGave = -1;
  // The first map's best pair: kept matches over the fewer corners of its two images.
  double cornerRepeat = 0.0;
};

// A reference's pose measured in its own image from a fiducial in view (a marker, a calibration
// board): refined from the matches like a marker's (params.refinePoses).
struct MeasuredPose {
  RigidPose worldToCamera;
  double reprojectionRmsPx = 0.0;  // of the fiducial's corners
};

struct MultiPreparation {
  MultiReferenceMap map;
  MultiPreparationReport report;
};

class MultiReferencePreparer {
 public:
  using Params = ReferencePreparerParams;
  // Called once per pair as soon as it has been matched or skipped.
  using PairProgress = std::function<void(const ReferencePairReport&)>;

  MultiReferencePreparer(PinholeCamera camera, Params params = {});  // throws on bad input

  // Poses from `marker`, detected in every image.
  MultiPreparation prepare(const std::vector<ReferenceImage>& images, const MarkerSpec& marker,
                           const PairProgress& progress = {}) const;
  // Poses measured in the images (one per image, e.g. captured live in the viewer from a marker
  // or board); poseSource is recorded in the map. The marker overload ends here.
  MultiPreparation prepare(const std::vector<ReferenceImage>& images,
                           const std::vector<MeasuredPose>& poses, const std::string& poseSource,
                           const PairProgress& progress = {}) const;
  // Known world->camera poses, one per image; poseSource is recorded in the map.
  MultiPreparation prepare(const std::vector<ReferenceImage>& images,
                           const std::vector<RigidPose>& poses, const std::string& poseSource,
                           const PairProgress& progress = {}) const;

  // The map's file name of reference `index` ("reference_03.png").
  static std::string viewFileName(int index);

 private:
  MultiPreparation build(const std::vector<ReferenceImage>& images,
                         const std::vector<RigidPose>& poses, const std::string& poseSource,
                         MultiPreparationReport report, const PairProgress& progress,
                         bool posesGiven) const;
  // Corners with cornerParams, every pair matched, the tracks merged into points (no pose
  // refinement, no keypoint layer, no minimum).
  MultiPreparation matchAndMerge(const std::vector<ReferenceImage>& images,
                                 const std::vector<RigidPose>& poses, const std::string& poseSource,
                                 MultiPreparationReport report, const PairProgress& progress,
                                 const CornerParams& cornerParams, bool denser) const;
  void checkImages(const std::vector<ReferenceImage>& images) const;

  PinholeCamera camera_;
  Params params_;
};

}  // namespace reftrack
