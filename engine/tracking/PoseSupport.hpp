#pragma once
// PoseSupport: how well the 3D-2D matches of a frame pin its pose down, in pixels: the
// a-posteriori standard deviation of the reprojected support points under the measurement-only
// pose covariance s^2 (J^T J)^-1, where J stacks the projections' derivatives by x_Ak and
// s^2 = SSE / (2N - 6) is the residual variance actually observed. Few matches, large residuals
// (blurred corners) or a poor spread all raise it; the tracker refuses a pose above a limit.
#include <optional>
#include <span>

#include "engine/estimation/RegularizedPoseEstimator.hpp"
#include "engine/geometry/PinholeCamera.hpp"

namespace reftrack {

// RMS over the support points of the SD (pixels, per image axis) of their reprojection under T;
// nullopt with fewer than 4 points or a rank-deficient J (no support at all).
std::optional<double> reprojectionSupportSdPx(const PinholeCamera& camera, const RigidPose& T,
                                              std::span<const ThreeViewMatch> support);

}  // namespace reftrack
