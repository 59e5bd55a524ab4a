#pragma once
// UnpreparedInitializer (`prepare --unprepared`, the viewer's Map panel without a marker or
// board): a reference map of an unprepared scene — no marker, no board, no given poses — from
// two views and one distance the user knows. The first two references' relative pose comes from
// their own keypoint matches (TwoViewMotion: essential matrix, five-point RANSAC, with its checks
// for textureless views, pure rotations and too little parallax), then refinementRounds times:
// their corners are matched epipolar-guided on that pose and triangulated (MultiReferencePreparer,
// the first round with wider gates) and the pose refined from those matches (ReferencePoseRefiner:
// reference 0 held, reference 1 free under weak priors; the baseline's length kept). The world
// frame is put on the scene's dominant plane (ScenePlacement of those points: origin at the plane
// points' centre, z along its normal toward the cameras, x along the first camera's x laid onto
// the plane; without a plane the first camera's frame), the scale set by the MetricScale (the
// baseline's length, or two points of the first reference intersected with the plane), and the
// map prepared as `prepare --poses` prepares one (MultiReferencePreparer with those poses; its
// keypoint layer too). Further references are located in that map (Relocaliser) and added as
// `extend` adds them (MapExtender::add: matching and bundle adjustment, the first two held), and
// a closing bundle adjustment runs. Bad input or a pair that cannot start a map throws
// reftrack::Error with what to do.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/UnpreparedMapParams.hpp"
#include "engine/mapping/MapExtender.hpp"
#include "engine/mapping/MetricScale.hpp"
#include "engine/mapping/ScenePlacement.hpp"
#include "engine/reference/MultiReferencePreparer.hpp"
#include "engine/reference/TwoViewMotion.hpp"

namespace reftrack {

// One round of corner matching on the current pose and its refinement.
struct UnpreparedRound {
  int points = 0;                              // triangulated from the corner matches
  double rmsBeforePx = 0.0, rmsAfterPx = 0.0;  // their reprojection RMS around the refinement
  double turnedDeg = 0.0;                      // how far the refinement turned reference 1
  double directionDeg = 0.0;                   // ... and turned the direction of its translation
};

struct UnpreparedMapReport {
  TwoViewMotion motion;  // from the keypoints (the essential matrix)
  std::string start;     // the start the map was refined from ("essential matrix", ...)
  int starts = 0;        // the starts tried
  std::vector<UnpreparedRound> rounds;  // of that start
  bool onPlane = false;   // the world frame is on the dominant plane (else the first camera's)
  std::string planeNote;  // without a plane: why
  int planePoints = 0, planeConsideredPoints = 0;
  double planeRmsMetres = 0.0;
  MetricScale scale;
  double baselineMetres = 0.0;  // between references 0 and 1 in the map
  // Distance: the two marked points on the plane (world, metres).
  Eigen::Vector3d distanceFirst = Eigen::Vector3d::Zero(), distanceSecond = Eigen::Vector3d::Zero();
  // Relative pose of reference 1 to 0 before any refinement and in the map (first -> second).
  RigidPose essentialPose, refinedPose;
  std::vector<AddedReference> added;  // references 2.. (as `extend` adds them)
  std::optional<BundleAdjustmentReport> closingAdjustment;  // with added references
};

struct UnpreparedMap {
  MultiPreparation prepared;  // the map (its report: the final preparation's)
  UnpreparedMapReport report;
};

class UnpreparedInitializer {
 public:
  // A line per step as it starts ("keypoints and essential matrix", "matching round 1", ...).
  using StepProgress = std::function<void(const std::string&)>;

  // params.preparation prepares the map, params.tracker.relocalisation locates references 2..,
  // params.extension and bundleAdjustment add them. Throws reftrack::Error on bad params/camera.
  UnpreparedInitializer(PinholeCamera camera, MapExtenderParams params,
                        UnpreparedMapParams unprepared = {});

  // The map from images (N >= 2; the first two start it) and the scale. `pairs` sees the final
  // preparation's pair (as `prepare` prints it).
  UnpreparedMap build(const std::vector<ReferenceImage>& images, const MetricScale& scale,
                      const StepProgress& progress = {},
                      const MultiReferencePreparer::PairProgress& pairs = {}) const;
  // The steps build() reports for `references` images.
  int steps(int references) const;

  const UnpreparedMapParams& unpreparedParams() const { return unprepared_; }

 private:
  struct Refined {
    std::string start;
    RigidPose second;                     // first -> second camera
    RigidPose worldToFirst;               // the dominant plane's frame (or the first camera's)
    std::optional<ScenePlacement> plane;  // in the first camera's frame
    std::string noPlane;                  // without a plane: why
    std::vector<Eigen::Vector3d> points;  // the last round's, in the first camera's frame
    std::vector<UnpreparedRound> rounds;
    double cost = 0.0;                          // lower: the corners fit better (see refine())
    std::vector<RigidPose> cornerPlaneMotions;  // of the last round's corner matches
  };
  Refined refine(const std::vector<ReferenceImage>& pair, const RigidPose& start, double length,
                 const StepProgress& step) const;

  PinholeCamera camera_;
  MapExtenderParams params_;
  UnpreparedMapParams unprepared_;
};

}  // namespace reftrack
