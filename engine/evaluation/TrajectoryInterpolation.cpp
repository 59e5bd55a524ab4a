#include "engine/evaluation/TrajectoryInterpolation.hpp"

#include <algorithm>

#include "engine/core/Error.hpp"

namespace reftrack {

TumTrajectory interpolateTrajectory(const TumTrajectory& trajectory,
                                    const std::vector<double>& times, double maxGap) {
  if (!(maxGap >= 0.0)) throw Error("interpolation gap must be >= 0 seconds");
  std::vector<StampedPose> poses = trajectory.poses;
  std::stable_sort(poses.begin(), poses.end(), [](const StampedPose& a, const StampedPose& b) {
    return a.timestamp < b.timestamp;
  });
  TumTrajectory out;
  for (double t : times) {
    const auto after =
        std::lower_bound(poses.begin(), poses.end(), t,
                         [](const StampedPose& p, double time) { return p.timestamp < time; });
    if (after == poses.end()) continue;
    if (after->timestamp == t) {
      out.poses.push_back({t, after->worldToCamera});
      continue;
    }
    if (after == poses.begin()) continue;
    const StampedPose& before = *(after - 1);
    const double span = after->timestamp - before.timestamp;
    if (span > maxGap) continue;
    const double w = (t - before.timestamp) / span;
    const RigidPose a = before.worldToCamera.inverse(), b = after->worldToCamera.inverse();
    const Eigen::Quaterniond q = a.quaternion().slerp(w, b.quaternion());
    const Eigen::Vector3d c = (1.0 - w) * a.translation() + w * b.translation();
    out.poses.push_back({t, RigidPose(q, c).inverse()});
  }
  return out;
}

}  // namespace reftrack
