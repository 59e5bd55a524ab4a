#pragma once
// interpolateTrajectory: a trajectory resampled at given times — for each time, the camera centre
// interpolated linearly and the orientation spherically (slerp) between the two poses around it —
// so a ground truth recorded at its own rate (motion capture at 100-200 Hz) gets one pose per
// camera frame. A time outside the trajectory, or between two poses more than maxGap seconds
// apart (a tracking dropout of the motion capture), gets no pose. Times need not be sorted; the
// result keeps their order.
#include <vector>

#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack {

// Throws reftrack::Error when maxGap is negative or NaN.
TumTrajectory interpolateTrajectory(const TumTrajectory& trajectory,
                                    const std::vector<double>& times, double maxGap);

}  // namespace reftrack
