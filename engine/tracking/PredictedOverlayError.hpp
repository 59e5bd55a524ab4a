#pragma once
// PredictedOverlayError (issue 32): the overlay error in pixels that a pose covariance predicts —
// the RMS over an object's points of each point's expected image displacement
// sqrt(trace(J_i Sigma J_i^T)), J_i the 2x6 Jacobian of the point's ideal pinhole projection (K
// alone, no lens) with respect to the pose's 6-vector (t, r), r axis-angle, the parameterisation
// of RigidPose::toVector6. To first order this is the RMS displacement of the drawn points when
// the pose is drawn from N(pose, Sigma). Points behind the camera are skipped.
//
// `pose` maps the points' frame to the camera and `covariance` is that of pose.toVector6():
// the tracker's Omega_k of x_Ak goes with pose = T_Ak and the points in camera A's frame
// (T_A X_world); Tracker::Result::covariance goes with pose = worldToCamera and world points. The
// two give the same figure to first order (the second is the first carried to the world frame).
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "engine/config/PoseParams.hpp"
#include "engine/estimation/MotionModel.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/RigidPose.hpp"
#include "engine/tracking/PoseTracker.hpp"

namespace reftrack {

// d(pixel of `point`)/d(pose.toVector6()), exact (automatic differentiation). `point` must lie in
// front of the camera (z > 0 after the pose).
Eigen::Matrix<double, 2, 6> projectionJacobian(const PinholeCamera& camera, const RigidPose& pose,
                                               const Eigen::Vector3d& point);

// sqrt(mean over the points in front of the camera of trace(J_i Sigma J_i^T)) in pixels; nullopt
// when no point is in front (or none is given). Throws reftrack::Error when the covariance is not
// finite.
std::optional<double> predictedOverlayErrorPx(const PinholeCamera& camera, const RigidPose& pose,
                                              const Matrix6d& covariance,
                                              const std::vector<Eigen::Vector3d>& points);

// The true overlay error the prediction is compared with: the mean pixel distance of the points
// projected with K alone, estimated vs true world->camera pose (bench-real's cube error), leaving
// out points behind either camera; nullopt when none is in front of both.
std::optional<double> overlayErrorPx(const PinholeCamera& camera, const RigidPose& truth,
                                     const RigidPose& estimate,
                                     const std::vector<Eigen::Vector3d>& worldPoints);

// The object the tracker predicts the overlay error of when it is told none: the 8 corners of the
// box that holds the central part of the map's points (world frame; per axis from the 10th to the
// 90th percentile, so a few stray points far away do not blow it up) — content drawn amid the
// mapped scene, at the scene's size. Not the map points themselves: the pose is fitted to them,
// so they are the best-fixed places, and they crowd where the texture is. Empty without points.
std::vector<Eigen::Vector3d> centralBoxCorners(const std::vector<Eigen::Vector3d>& points);

// Omega_k rescaled a posteriori: Omega_k's figures come from the corner-variance model's noise and
// count the temporal prior as independent information, while the errors of real frames are
// several times larger and shared from frame to frame (the map's). The tracker's support SD
// (PoseTrackingResult::supportSdPx: the reprojection SD of the three-view inliers under the
// matches alone, their residual variance as observed) over the SD Omega_k predicts at the same
// points (supportPointsA; both as 2-D RMS) is the factor Omega_k's SDs are off by in this frame.
// 1 without support points or support SD.
double aPosterioriFactor(const PinholeCamera& camera, const PoseTrackingResult& result);

struct OverlayErrorCheck {
  // The predicted error of Omega_k, times aPosterioriFactor and pose.predicted_error_scale;
  // nullopt unless tracking with a pose (or when every point is behind the camera).
  std::optional<double> predictedErrorPx;
  // Non-empty when predictedErrorPx exceeds pose.max_predicted_error_px (> 0): the pose should not
  // be drawn as if exact, e.g. "predicted overlay error 7.2 px > pose.max_predicted_error_px 3".
  std::string uncertainReason;
};

// A pair tracker's result (Omega_k of x_Ak, T_Ak, T_k, its support) checked for an object given by
// its world points: the prediction from T_Ak, Omega_k and the points carried into camera A's
// frame, rescaled a posteriori and calibrated.
OverlayErrorCheck checkPredictedOverlayError(const PinholeCamera& camera,
                                             const PoseTrackingResult& result,
                                             const std::vector<Eigen::Vector3d>& worldPoints,
                                             const PoseParams& params);

}  // namespace reftrack
