#include "engine/features/CornerGrid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace reftrack {
namespace {

// The grid must return exactly what a brute-force scan returns, for windows of any size and for
// points and windows reaching past the image.
TEST(CornerGrid, QueryEqualsBruteForce) {
  cv::RNG rng(7);
  std::vector<cv::Point2f> pts;
  for (int i = 0; i < 500; ++i)
    pts.emplace_back(rng.uniform(-20.f, 660.f), rng.uniform(-20.f, 500.f));
  const CornerGrid grid(pts, {640, 480}, 32);
  std::vector<int> got;
  for (int q = 0; q < 200; ++q) {
    const cv::Point2d c(rng.uniform(-50.0, 690.0), rng.uniform(-50.0, 530.0));
    const double hw = rng.uniform(1.0, 80.0), hh = rng.uniform(1.0, 80.0);
    grid.query(c, hw, hh, got);
    std::vector<int> expected;
    for (int i = 0; i < 500; ++i)
      if (std::abs(pts[static_cast<std::size_t>(i)].x - c.x) <= hw &&
          std::abs(pts[static_cast<std::size_t>(i)].y - c.y) <= hh)
        expected.push_back(i);
    std::sort(got.begin(), got.end());
    EXPECT_EQ(got, expected);
  }
}

// Points outside the image are kept in the border cells and found by windows reaching them; a
// centre far away (or not finite) returns nothing instead of overflowing the cell arithmetic; an
// empty grid returns nothing.
TEST(CornerGrid, OutsidePointsFarCentresAndEmptyGrid) {
  const std::vector<cv::Point2f> pts = {{-5.f, 10.f}, {700.f, 470.f}, {320.f, -3.f}, {10.f, 10.f}};
  const CornerGrid grid(pts, {640, 480}, 32);
  std::vector<int> got;
  grid.query({0.0, 10.0}, 6.0, 1.0, got);
  std::sort(got.begin(), got.end());
  EXPECT_EQ(got, (std::vector<int>{0}));
  grid.query({690.0, 470.0}, 20.0, 20.0, got);
  EXPECT_EQ(got, (std::vector<int>{1}));
  grid.query({320.0, 0.0}, 5.0, 5.0, got);
  EXPECT_EQ(got, (std::vector<int>{2}));
  grid.query({1e300, -1e300}, 1e299, 1e299, got);
  EXPECT_TRUE(got.empty());
  grid.query({std::nan(""), 10.0}, 5.0, 5.0, got);
  EXPECT_TRUE(got.empty());
  grid.query({10.0, 10.0}, std::nan(""), 5.0, got);
  EXPECT_TRUE(got.empty());
  const CornerGrid none({}, {640, 480}, 32);
  EXPECT_TRUE(none.empty());
  none.query({10.0, 10.0}, 100.0, 100.0, got);
  EXPECT_TRUE(got.empty());
}

}  // namespace
}  // namespace reftrack
