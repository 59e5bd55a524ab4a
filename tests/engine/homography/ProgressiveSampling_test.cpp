#include "engine/homography/ProgressiveSampling.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(ProgressiveSampling, RanksByQualityAndGrowsThePoolToAllMatches) {
  const std::vector<float> quality{0.2f, 0.9f, 0.5f, 0.9f, 0.1f, 0.7f, 0.3f, 0.8f, 0.6f, 0.4f};
  const ProgressiveSampling s(quality, 10, true, 70, 4, 5);
  // Best first; ties keep the input order.
  EXPECT_EQ(s.matchAt(0), 1);
  EXPECT_EQ(s.matchAt(1), 3);
  EXPECT_EQ(s.matchAt(2), 7);
  EXPECT_EQ(s.matchAt(9), 4);
  // T C(n_t, 4) / C(10, 4) >= t + 1 with T = 70, C(10, 4) = 210: n_t = 5 while t + 1 <= 1.67
  // (C(5, 4) = 5), 6 up to 5 (C(6, 4) = 15), ..., all 10 at the last iteration.
  EXPECT_EQ(s.pool(0), 5);
  EXPECT_EQ(s.pool(1), 6);
  EXPECT_EQ(s.pool(4), 6);
  EXPECT_EQ(s.pool(5), 7);
  EXPECT_EQ(s.pool(69), 10);
  for (int t = 1; t < 70; ++t) EXPECT_GE(s.pool(t), s.pool(t - 1));
}

TEST(ProgressiveSampling, WithoutQualityOrSwitchedOffDrawsFromAll) {
  const ProgressiveSampling none({}, 6, true, 70, 2, 3);
  EXPECT_EQ(none.pool(0), 6);
  EXPECT_EQ(none.matchAt(4), 4);
  const ProgressiveSampling off({0.1f, 0.9f, 0.5f}, 3, false, 70, 2, 2);
  EXPECT_EQ(off.pool(0), 3);
  EXPECT_EQ(off.matchAt(0), 0);
}

TEST(ProgressiveSampling, MatchListsMustAgree) {
  EXPECT_NO_THROW(requireMatchLists("x", {{1, 2}}, {{3, 4}}, {}));
  EXPECT_NO_THROW(requireMatchLists("x", {{1, 2}}, {{3, 4}}, {0.5f}));
  EXPECT_THROW(requireMatchLists("x", {{1, 2}}, {}, {}), Error);
  EXPECT_THROW(requireMatchLists("x", {{1, 2}}, {{3, 4}}, {0.5f, 0.6f}), Error);
}
