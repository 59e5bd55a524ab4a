#pragma once
// The fundamental matrix of a calibrated pair from their relative pose (paper Eq. 1-2, SPEC §2):
// F = K^-T [t]x R K^-1 for T = [R | t] mapping camera-1 points into camera 2, so that
// ~p2^T F ~p1 = 0 for corresponding (undistorted) pixels.
#include <Eigen/Core>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

Eigen::Matrix3d skewSymmetric(const Eigen::Vector3d& v);
Eigen::Matrix3d fundamentalMatrix(const Eigen::Matrix3d& K, const RigidPose& oneToTwo);

}  // namespace reftrack
