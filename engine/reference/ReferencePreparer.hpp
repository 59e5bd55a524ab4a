#pragma once
// ReferencePreparer: the offline preparation of paper Sec. 2/3.3 (SPEC §1) — from two reference
// images and their world->camera poses (given, or from an ArUco marker seen in both) to a
// ReferenceMap: corners of both images (many more than a tracked frame gets, so the tracker has
// plenty to match), epipolar-guided A<->B matches and their triangulated 3D points.
// Every bad input (unreadable or mis-sized image, missing marker, no baseline, too few matches)
// throws reftrack::Error naming the image or the parameter at fault.
#include <filesystem>
#include <optional>
#include <string>

#include "engine/config/CornerParams.hpp"
#include "engine/config/RelocalisationParams.hpp"
#include "engine/features/Corner.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/reference/EpipolarGuidedMatcher.hpp"
#include "engine/reference/MarkerPoseEstimator.hpp"
#include "engine/reference/MarkerSpec.hpp"
#include "engine/reference/ReferenceMap.hpp"
#include "engine/reference/ReferencePoseRefiner.hpp"

namespace reftrack {

struct ReferencePreparerParams {
  // Six times the per-frame corner count (55 at 320x240) at half the spacing, found at full
  // resolution down to 1e-4 of the strongest Harris response (a tenth of its contrast): the
  // tracker's wide-baseline matching needs many reference corners with 3D points, and a printed
  // marker's black-white corners would otherwise crowd out the scene's weaker ones (real
  // hand-held card-on-table clip: 1e-3 gives 34 map points, 1e-4 gives 44 and tracks every
  // frame; the simulator's 640x480 map: 615 points).
  CornerParams corners = [] {
    CornerParams c;
    c.countAt320x240 = 330;
    c.minDistancePx = 4.0;
    c.quality = 1e-4;
    c.detectAtPaperScale = false;
    return c;
  }();
  EpipolarMatcherParams matching;
  MarkerPoseParams marker;
  double minBaselineMetres = 0.01;  // reference cameras closer than this cannot triangulate
  int minMatches = 30;              // fewer kept matches than this is a failed preparation
  // N references (MultiReferencePreparer). A pair is matched only when the angle between the
  // two optical axes is at most this: the warped NCC windows of EpipolarGuidedMatcher model
  // planes slanted up to matching.slant_deg (50) and wider view changes correlate poorly.
  double maxPairViewAngleDeg = 60.0;
  // ... and its matches are merged into the map only when at least this many survive (fewer:
  // too little overlap to trust them; the N = 2 preparation needs min_matches instead).
  int minPairMatches = 12;
  // A point seen by 3+ references is re-triangulated from all its corners; an observation
  // reprojecting farther than this from its corner is dropped. Default: a pair's own gates
  // (matching.max_peak_offset_px 1.5 between B's corner and the peak it triangulated from, plus
  // matching.max_reprojection_error_px 1.0) admit a corner up to 2.5 px from its point.
  double maxTrackReprojectionErrorPx = 2.5;
  // A map (MultiReferencePreparer) of fewer points than this is made again from denser corners
  // (three times the count down to 1e-6 of the strongest Harris response, half the spacing), and
  // the map with more points is kept. Soft, compressed frames repeat few of the strongest corners
  // between two views (`experiment-reference-pair`, Kinect 40 cm / 15 degree pairs: 0-53 points
  // -> 54-105, found in other frames as accurately as SIFT matches' points); the sharp clips' maps
  // (116-177 points) are left as they are (the denser desk map tracked worse: README). Only when
  // the corners repeat poorly, too: the best pair kept at most denser_corner_max_repeat of the
  // fewer corners of its two images (Kinect 50/105: 37 of 405, 0.09). A sharp view that is
  // simply small keeps its map (the postcard clip's card: 43 of 167, 0.26; its denser map of 146
  // points tracked frames 0-29 at 0.82 px cube error, 4 lost, instead of 0.31 px, none lost).
  int targetPoints = 100;
  double denserCornerMaxRepeat = 0.15;
  int denserCornerCount = 1000;  // at 320x240, as corners.count
  double denserCornerQuality = 1e-6;
  double denserCornerMinDistancePx = 2.0;
  CornerParams denserCorners() const {
    CornerParams c = corners;
    c.countAt320x240 = denserCornerCount;
    c.quality = denserCornerQuality;
    c.minDistancePx = denserCornerMinDistancePx;
    return c;
  }
  // Refine the given (marker / --poses) poses of references 1..N-1 from the map's own matches,
  // reference 0 and the scale held by the given poses (ReferencePoseRefiner), fitting the
  // correlation peaks the points were triangulated from (both the N- and the two-reference
  // preparation). Measured (README): real postcard clip, grid error mean 0.81 -> 0.61 px; 4 cm
  // simulator pair, B 0.3 deg off, cube error 0.65 -> 0.12 px; exact poses: within 0.005 px of
  // the mean and 0.02 px of the p95, depth RMS 2.93 -> 2.91 mm.
  bool refinePoses = true;
  // ... and the same for poses given by the caller (`prepare --poses`: motion capture, a
  // fiducial's track, a dataset's ground truth), off by default: such poses are usually good to
  // their stated accuracy and the adjustment moved them by more (real desk clip, references 0 and
  // 40: reference 1 moved 0.80 mm and 0.128 deg, and the cube error rose 0.50 -> 0.53 px; the
  // issue's held-out clips: 0.385 -> 0.538, 0.196 -> 0.332, 0.867 -> 0.924 px).
  bool refineGivenPoses = false;
  // Whether the preparation's poses are to be refined: refinePoses for marker poses,
  // refineGivenPoses for given ones.
  bool refines(bool posesGiven) const { return posesGiven ? refineGivenPoses : refinePoses; }
  ReferencePoseRefinerParams poseRefinement;
  // The keypoint layer an N-reference map carries for relocalisation (buildReferenceKeypoints;
  // section `relocalisation`, as in the tracking parameters, whose keypoints must be the same
  // kind). enabled: false leaves the layer out. The two-reference preparation ignores it.
  RelocalisationParams relocalisation;

  void check() const;  // throws reftrack::Error naming the bad field
  // Sections corners, matching, marker, preparation, relocalisation.
  void write(cv::FileStorage& fs) const;
  // Missing keys keep their value; then check(). An unknown key or section throws, except the
  // top-level `otherSections` the caller reads from the same file itself.
  void read(const YamlNode& root, const std::vector<std::string>& otherSections = {});
  std::string toYaml() const;  // the whole set as YAML text (ReferenceMap's record)
  // Throws reftrack::Error naming the file and the key at fault.
  static ReferencePreparerParams load(const std::filesystem::path& file);
};

// One reference image with the name its errors use (usually the file path).
struct ReferenceImage {
  cv::Mat image;  // BGR or grey, 8-bit
  std::string name;
};

// Shared by the two- and N-reference preparations. Throws reftrack::Error naming the image when
// it is empty or not of the camera's size.
void checkReferenceImage(const ReferenceImage& image, const PinholeCamera& camera);
// Throws reftrack::Error naming both images when they are pixel for pixel the same (no baseline).
void checkDistinctReferenceImages(const ReferenceImage& a, const ReferenceImage& b);
// The corners of one reference image as the map stores them.
std::vector<ReferenceCorner> referenceCornersOf(const std::vector<Corner>& corners);

struct PreparationReport {
  std::optional<double> markerRmsA, markerRmsB;  // marker corner reprojection RMS (pixels)
  double baselineMetres = 0.0;                   // distance between the two camera centres
  EpipolarMatchStats matching;
  int occupiedGridCells = 0;  // cells of a 4x3 grid over image A holding a kept match
  std::optional<ReferencePoseRefinement> poseRefinement;  // when params.refines() (B refined)
};

struct Preparation {
  ReferenceMap map;
  PreparationReport report;
};

class ReferencePreparer {
 public:
  using Params = ReferencePreparerParams;

  ReferencePreparer(PinholeCamera camera, Params params = {});  // throws on bad input

  // Poses T_A, T_B from `marker`, detected in both images.
  Preparation prepare(const ReferenceImage& a, const ReferenceImage& b,
                      const MarkerSpec& marker) const;
  // Known world->camera poses; poseSource is recorded in the map (e.g. "poses references.txt").
  Preparation prepare(const ReferenceImage& a, const ReferenceImage& b, const RigidPose& T_A,
                      const RigidPose& T_B, const std::string& poseSource) const;

 private:
  Preparation triangulate(const ReferenceImage& a, const ReferenceImage& b, const RigidPose& T_A,
                          const RigidPose& T_B, const std::string& poseSource,
                          PreparationReport report, bool posesGiven) const;
  void checkImages(const ReferenceImage& a, const ReferenceImage& b) const;

  PinholeCamera camera_;
  Params params_;
};

}  // namespace reftrack
