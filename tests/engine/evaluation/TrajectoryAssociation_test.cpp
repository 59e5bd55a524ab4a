#include "engine/evaluation/TrajectoryAssociation.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {
TumTrajectory stamps(const std::vector<double>& t) {
  TumTrajectory traj;
  for (double s : t) traj.poses.push_back({s, RigidPose()});
  return traj;
}
}  // namespace

TEST(TrajectoryAssociation, PairsNearestWithinToleranceUsingEachEstimateOnce) {
  const TumTrajectory gt = stamps({0.0, 0.1, 0.2, 0.3, 0.4});
  // Unsorted estimates; 0.101 is nearest to 0.1; 0.33 is too far from 0.3; 0.398 serves 0.4.
  const TumTrajectory est = stamps({0.398, 0.101, 0.002, 0.33});
  const auto pairs = associateByTimestamp(gt, est, 0.005);
  ASSERT_EQ(pairs.size(), 3u);
  EXPECT_EQ(pairs[0].groundTruth, 0u);
  EXPECT_EQ(pairs[0].estimate, 2u);
  EXPECT_EQ(pairs[1].groundTruth, 1u);
  EXPECT_EQ(pairs[1].estimate, 1u);
  EXPECT_EQ(pairs[2].groundTruth, 4u);
  EXPECT_EQ(pairs[2].estimate, 0u);
  // One estimate between two close ground-truth stamps goes to the nearer one only.
  const auto single = associateByTimestamp(stamps({1.0, 1.004}), stamps({1.003}), 0.01);
  ASSERT_EQ(single.size(), 1u);
  EXPECT_EQ(single[0].groundTruth, 1u);
  EXPECT_THROW(associateByTimestamp(gt, est, -1.0), Error);
}
