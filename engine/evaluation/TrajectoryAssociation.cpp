#include "engine/evaluation/TrajectoryAssociation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/core/Error.hpp"

namespace reftrack {

std::vector<AssociatedPair> associateByTimestamp(const TumTrajectory& groundTruth,
                                                 const TumTrajectory& estimate,
                                                 double maxTimeDifference) {
  if (!(maxTimeDifference >= 0.0) || !std::isfinite(maxTimeDifference))
    throw Error("association: the maximum time difference must be a finite number >= 0");
  std::vector<std::size_t> order(estimate.poses.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return estimate.poses[a].timestamp < estimate.poses[b].timestamp;
  });
  const std::size_t none = std::numeric_limits<std::size_t>::max();
  // For every estimate, the ground-truth pose closest to it within the tolerance.
  std::vector<std::size_t> bestGt(estimate.poses.size(), none);
  std::vector<double> bestDiff(estimate.poses.size(), std::numeric_limits<double>::infinity());
  std::vector<std::size_t> candidate(groundTruth.poses.size(), none);
  for (std::size_t g = 0; g < groundTruth.poses.size(); ++g) {
    const double t = groundTruth.poses[g].timestamp;
    const auto it = std::lower_bound(order.begin(), order.end(), t, [&](std::size_t e, double v) {
      return estimate.poses[e].timestamp < v;
    });
    double best = std::numeric_limits<double>::infinity();
    for (auto j = it; j != order.end() && j - it < 2; ++j) {
      const double d = std::abs(estimate.poses[*j].timestamp - t);
      if (d < best) best = d, candidate[g] = *j;
    }
    if (it != order.begin()) {
      const double d = std::abs(estimate.poses[*(it - 1)].timestamp - t);
      if (d < best) best = d, candidate[g] = *(it - 1);
    }
    if (candidate[g] == none || best > maxTimeDifference) {
      candidate[g] = none;
      continue;
    }
    if (best < bestDiff[candidate[g]]) bestDiff[candidate[g]] = best, bestGt[candidate[g]] = g;
  }
  std::vector<AssociatedPair> pairs;
  for (std::size_t g = 0; g < groundTruth.poses.size(); ++g)
    if (candidate[g] != none && bestGt[candidate[g]] == g) pairs.push_back({g, candidate[g]});
  return pairs;
}

}  // namespace reftrack
