#pragma once
// lookAtPose: the world->camera pose (OpenCV axes: x right, y down, z forward) of a camera at
// `eye` whose optical axis passes through `target`, with image "up" as close to `up` as possible.
#include <Eigen/Core>

#include "engine/geometry/RigidPose.hpp"

namespace reftrack {

// Throws reftrack::Error when eye == target or the viewing direction is parallel to `up`.
RigidPose lookAtPose(const Eigen::Vector3d& eye, const Eigen::Vector3d& target,
                     const Eigen::Vector3d& up = Eigen::Vector3d::UnitZ());

}  // namespace reftrack
