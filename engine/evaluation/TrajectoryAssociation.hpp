#pragma once
// Timestamp association of two trajectories: each ground-truth pose is paired with the
// estimate nearest in time when that lies within maxTimeDifference seconds. Each estimate is used
// at most once (the closest ground-truth pose wins), so a slow tracker is not counted twice.
#include <cstddef>
#include <utility>
#include <vector>

#include "engine/geometry/TumTrajectory.hpp"

namespace reftrack {

struct AssociatedPair {
  std::size_t groundTruth = 0;  // index into the ground-truth poses
  std::size_t estimate = 0;     // index into the estimated poses
};

// Pairs in ground-truth order. Throws reftrack::Error when maxTimeDifference is negative or NaN.
std::vector<AssociatedPair> associateByTimestamp(const TumTrajectory& groundTruth,
                                                 const TumTrajectory& estimate,
                                                 double maxTimeDifference);

}  // namespace reftrack
