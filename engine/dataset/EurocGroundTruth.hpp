#pragma once
// readEurocGroundTruth: the ground truth of a EuRoC / ASL sequence
// (mav0/state_groundtruth_estimate0/data.csv: per line timestamp [ns], p_RS_R x y z [m],
// q_RS w x y z, then velocity and biases, which are ignored) — the body (IMU) pose in the world R
// — turned into camera poses through the camera's T_BS: camera-in-world = T_RS * T_BS.
// Timestamps in seconds. Throws reftrack::Error naming the file and line of a malformed entry.
#include <filesystem>

#include "engine/geometry/RigidPose.hpp"
#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack {

TumTrajectory readEurocGroundTruth(const std::filesystem::path& csv, const RigidPose& sensorToBody);

}  // namespace reftrack
