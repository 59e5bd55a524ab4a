#include "engine/relocalisation/RelocalisationBudget.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack {
namespace {

// Attempts of 40 ms against 3 ms per lost frame and a burst of 100 ms: the first three lost
// frames try (100 -> 63 -> 26 -> -11 ms), then one attempt whenever the bucket is back above 0:
// frame 6 (-11 + 3 * 4 > 0), then every 13th or 14th frame (40 / 3 = 13.3 on average).
TEST(RelocalisationBudget, AttemptsAtFirstOnEveryFrameThenBackOffToTheRate) {
  RelocalisationBudget budget(3.0, 100.0);
  std::vector<int> attempted;
  for (int frame = 0; frame < 60; ++frame)
    if (budget.lostFrame()) {
      attempted.push_back(frame);
      budget.spent(40.0);
    }
  ASSERT_GE(attempted.size(), 5u);
  EXPECT_EQ(attempted[0], 0);
  EXPECT_EQ(attempted[1], 1);
  EXPECT_EQ(attempted[2], 2);
  EXPECT_EQ(attempted[3], 6);
  for (std::size_t i = 4; i < attempted.size(); ++i) {
    EXPECT_GE(attempted[i] - attempted[i - 1], 13) << i;
    EXPECT_LE(attempted[i] - attempted[i - 1], 14) << i;
  }
  // Never more than the burst plus the rate per lost frame, and one attempt's overshoot.
  EXPECT_LE(budget.spentInAll(), 100.0 + 3.0 * 60 + 40.0);
  EXPECT_DOUBLE_EQ(budget.spentInAll(), 40.0 * static_cast<double>(attempted.size()));
}

TEST(RelocalisationBudget, TrackingAgainRefillsTheBurstAndCheapAttemptsAreNotHeldBack) {
  RelocalisationBudget budget(3.0, 100.0);
  ASSERT_TRUE(budget.lostFrame());
  budget.spent(500.0);  // one very long attempt: deep in debt
  EXPECT_FALSE(budget.lostFrame());
  budget.refill();
  EXPECT_TRUE(budget.lostFrame());
  // Attempts costing less than the rate (a black frame: no keypoints) come on every frame.
  budget.refill();
  for (int frame = 0; frame < 100; ++frame) {
    ASSERT_TRUE(budget.lostFrame()) << frame;
    budget.spent(1.0);
  }
  // The bucket never holds more than the burst and one frame's share.
  for (int frame = 0; frame < 1000; ++frame) budget.lostFrame();
  EXPECT_LE(budget.available(), 103.0);
}

TEST(RelocalisationBudget, AZeroBurstStillTriesTheFirstLostFrame) {
  RelocalisationBudget budget(2.0, 0.0);
  EXPECT_TRUE(budget.lostFrame());
  budget.spent(10.0);
  int attempts = 0;
  for (int frame = 0; frame < 50; ++frame) attempts += budget.lostFrame() ? 1 : 0;
  EXPECT_GE(attempts, 1);  // the bucket is positive again after 6 frames and stays so untouched
  budget.spent(std::nan(""));
  budget.spent(-5.0);
  EXPECT_DOUBLE_EQ(budget.spentInAll(), 10.0);
}

// A reserve of half the 100 ms burst: attempts of 40 ms on any frame stop once the bucket is down
// to 50 ms and come whenever it is back above it; the 50 ms stay for a frame that looks like the
// scene, which may then try at once (reserveHolds). Spent in all: still at most the burst, the
// rate per lost frame and one attempt's overshoot.
TEST(RelocalisationBudget, AReserveIsKeptForFramesThatLookLikeTheScene) {
  RelocalisationBudget budget(3.0, 100.0, 0.5);
  std::vector<int> attempted;
  for (int frame = 0; frame < 60; ++frame)
    if (budget.lostFrame()) {
      attempted.push_back(frame);
      budget.spent(40.0);
    }
  ASSERT_GE(attempted.size(), 4u);
  EXPECT_EQ(attempted[0], 0);   // 103 -> 63
  EXPECT_EQ(attempted[1], 1);   // 66 -> 26: the reserve is reached
  EXPECT_EQ(attempted[2], 10);  // 26 + 3 * 9 = 53 > 50
  for (std::size_t i = 3; i < attempted.size(); ++i) {
    EXPECT_GE(attempted[i] - attempted[i - 1], 13) << i;
    EXPECT_LE(attempted[i] - attempted[i - 1], 14) << i;
  }
  // Between attempts the reserve holds: a frame that looks like the scene may try at once.
  EXPECT_FALSE(budget.lostFrame());
  EXPECT_TRUE(budget.reserveHolds());
  // Once it is spent, neither kind of frame tries until the bucket is positive again.
  budget.spent(budget.available() + 1.0);
  EXPECT_FALSE(budget.reserveHolds());
  EXPECT_FALSE(budget.lostFrame());
  EXPECT_LE(budget.spentInAll(), 100.0 + 3.0 * 62 + 40.0);
}

TEST(RelocalisationBudget, BadRatesAreClearErrors) {
  EXPECT_THROW(RelocalisationBudget(3.0, 100.0, 1.0), Error);
  EXPECT_THROW(RelocalisationBudget(3.0, 100.0, -0.1), Error);
  EXPECT_THROW(RelocalisationBudget(3.0, 100.0, std::nan("")), Error);
  EXPECT_THROW(RelocalisationBudget(-1.0, 10.0), Error);
  EXPECT_THROW(RelocalisationBudget(1.0, std::nan("")), Error);
  EXPECT_THROW(RelocalisationBudget(INFINITY, 10.0), Error);
  RelocalisationBudget budget(1.0, 10.0);
  EXPECT_THROW(budget.configure(1.0, -2.0), Error);
}

}  // namespace
}  // namespace reftrack
