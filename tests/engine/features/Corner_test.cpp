#include "engine/features/Corner.hpp"

#include <gtest/gtest.h>

using namespace reftrack;

TEST(Corner, PositionsKeepOrder) {
  const std::vector<Corner> corners = {{{1.5f, 2.0f}, 3.0f, 4.0f}, {{7.0f, 8.25f}, 1.0f, 0.0f}};
  const auto p = positionsOf(corners);
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0], cv::Point2f(1.5f, 2.0f));
  EXPECT_EQ(p[1], cv::Point2f(7.0f, 8.25f));
  EXPECT_TRUE(positionsOf({}).empty());
}
