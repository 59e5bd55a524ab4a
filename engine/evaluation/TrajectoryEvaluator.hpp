#pragma once
// TrajectoryEvaluator: compares an estimated camera trajectory with ground truth (both TUM files,
// world = marker frame, so no alignment unless asked: `alignment` none (default), se3 — the rigid
// transform, or sim3 — rigid plus scale, that best maps the estimated camera centres onto the true
// ones (Umeyama least squares), as other trajectory tools offer; every error below is measured
// after it). Reports
//  - ATE: per associated frame, the camera-centre distance (mm) and the rotation angle (deg);
//  - RPE: per consecutive pair of associated frames, the error of the relative motion
//    E = D_gt^-1 D_est with D = T_k T_{k-1}^-1 (translation mm, rotation deg);
//  - cube reprojection error (needs the camera): a virtual cube of side cubeSide standing at
//    cubeBase (default the world origin) along world +z (up out of the marker), vertices projected
//    ideally (K, no lens
//    distortion) through both poses; statistics over all vertices of all frames (pixels);
//  - jitter: for runs of three consecutive ground-truth frames that all have an estimate, the
//    second difference a_k = e_{k+1} - 2 e_k + e_{k-1} of the cube-vertex error e_k (estimate minus
//    truth, camera frame) removes the smooth motion and any slowly varying bias; for white noise
//    of SD s per coordinate, var(a) = 6 s^2, so jitter = sqrt(mean(a^2) / 6) (mm, and px in the
//    image when the camera is given);
//  - tracked fraction: ground-truth frames with an associated estimate.
#include <optional>
#include <string>
#include <vector>

#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack {

// Se3Views: the rigid transform that best maps where the estimated cameras look onto where the
// true ones do — per frame, the camera centre and three points of its view (on the optical axis
// and beside it, at the median distance of the true centres from the world origin), Umeyama over
// them all — so the orientations count as well as the centres. On a short hand-held clip the
// centres alone leave the world's rotation poorly determined: the desk clip's map built from its
// own true poses scores 0.405 px unaligned and 1.232 px after se3.
enum class TrajectoryAlignment { None, Se3, Sim3, Se3Views };
// "none" | "se3" | "sim3" | "se3-views"; parse throws reftrack::Error naming the accepted values.
std::string toString(TrajectoryAlignment alignment);
TrajectoryAlignment parseTrajectoryAlignment(const std::string& text);

struct EvaluationParams {
  double maxTimeDifference = 0.005;  // s; association tolerance (half a frame at 100 Hz)
  TrajectoryAlignment alignment = TrajectoryAlignment::None;  // of the estimate to the truth
  double cubeSide = 0.1;  // m; the virtual cube for reprojection error and jitter
  // The centre of the cube's base (ground-truth world, m); it stands on it along world +z.
  Eigen::Vector3d cubeBase = Eigen::Vector3d::Zero();

  void check() const;  // throws reftrack::Error naming the bad field
};

struct ErrorStats {
  std::size_t count = 0;
  double rmse = 0, mean = 0, median = 0, p95 = 0, max = 0;
  // Statistics of `values` (all zero with count 0 when empty). p95 by linear interpolation.
  static ErrorStats of(std::vector<double> values);
};

struct FrameEvaluation {
  double timestamp = 0;           // ground-truth timestamp (s)
  double translationErrorMm = 0;  // ATE of this frame
  double rotationErrorDeg = 0;
  std::optional<double> cubeErrorPx;                          // mean over the visible cube vertices
  Eigen::Vector3d trueCentre = Eigen::Vector3d::Zero();       // camera centres in the (aligned)
  Eigen::Vector3d estimatedCentre = Eigen::Vector3d::Zero();  // world, m
};

struct TrajectoryEvaluation {
  std::size_t groundTruthFrames = 0, estimateFrames = 0, associatedFrames = 0;
  double trackedFraction = 0;
  ErrorStats ateTranslationMm, ateRotationDeg;
  ErrorStats rpeTranslationMm, rpeRotationDeg;
  std::optional<ErrorStats> cubeErrorPx;  // with a camera
  std::optional<double> jitterMm, jitterPx;
  bool aligned = false;  // alignment other than none
  // Estimate world -> ground-truth world: X_gt = scale * R X_est + t (identity for none; scale 1
  // for se3).
  RigidPose alignment;
  double alignmentScale = 1.0;
  std::vector<FrameEvaluation> frames;  // one per associated frame, in ground-truth order
  std::vector<double> rpeTimestamps;    // ground-truth timestamp of each RPE pair's second frame
  std::vector<double> rpeTranslationMmPerPair, rpeRotationDegPerPair;
};

// Throws reftrack::Error when either trajectory is empty or nothing associates.
TrajectoryEvaluation evaluateTrajectory(const TumTrajectory& groundTruth,
                                        const TumTrajectory& estimate,
                                        const EvaluationParams& params,
                                        const PinholeCamera* camera = nullptr);

// The eight vertices of the cube of side `side` standing on the world z = 0 plane at the origin.
std::vector<Eigen::Vector3d> cubeVertices(double side);

}  // namespace reftrack
