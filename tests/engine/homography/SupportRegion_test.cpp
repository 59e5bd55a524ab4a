#include "engine/homography/SupportRegion.hpp"

#include <gtest/gtest.h>

using namespace reftrack;

TEST(SupportRegion, HoldsTheInliersHullWithItsMargin) {
  const SupportRegion whole;
  EXPECT_TRUE(whole.whole());
  EXPECT_TRUE(whole.contains({-1e6f, 1e6f}));
  EXPECT_TRUE(SupportRegion({}, 5.0).whole());
  const SupportRegion square({{10, 10}, {110, 10}, {110, 110}, {10, 110}, {60, 60}}, 5.0);
  EXPECT_FALSE(square.whole());
  EXPECT_EQ(square.hull().size(), 4u);  // the inner point is not on the hull
  EXPECT_DOUBLE_EQ(square.hullArea(), 10000.0);
  EXPECT_TRUE(square.contains({60, 60}));
  EXPECT_TRUE(square.contains({114, 60}));   // within the 5 px margin
  EXPECT_FALSE(square.contains({116, 60}));  // beyond it
  // On a pyramid level (x 1/2): positions and margin halved.
  const SupportRegion level = square.scaled(0.5);
  EXPECT_DOUBLE_EQ(level.hullArea(), 2500.0);
  EXPECT_TRUE(level.contains({56.5f, 30}));
  EXPECT_FALSE(level.contains({58.5f, 30}));
  EXPECT_TRUE(level.scaled(1.0).contains({30, 30}));
}

TEST(SupportRegion, TwoPointsGiveTheirSegmentsMargin) {
  const SupportRegion segment({{0, 0}, {100, 0}}, 4.0);
  EXPECT_DOUBLE_EQ(segment.hullArea(), 0.0);
  EXPECT_TRUE(segment.contains({50, 3.5f}));
  EXPECT_FALSE(segment.contains({50, 4.5f}));
  EXPECT_FALSE(segment.contains({105, 0}));
  EXPECT_NEAR(supportMargin({640, 480}), 40.0, 1e-9);  // 5% of the 800 px diagonal
}
