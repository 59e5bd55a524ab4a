#include "engine/tracking/CornerGrid.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace reftrack {
namespace {

// The grid must return exactly what a brute-force scan returns, for windows of any size.
TEST(CornerGrid, QueryEqualsBruteForce) {
  cv::RNG rng(7);
  std::vector<cv::Point2f> pts;
  for (int i = 0; i < 500; ++i) pts.emplace_back(rng.uniform(0.f, 640.f), rng.uniform(0.f, 480.f));
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

}  // namespace
}  // namespace reftrack
