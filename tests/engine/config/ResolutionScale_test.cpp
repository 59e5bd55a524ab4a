#include "engine/config/ResolutionScale.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "engine/config/CornerParams.hpp"
#include "engine/config/WideBaselineParams.hpp"

using namespace reftrack;

TEST(ResolutionScale, CountsScaleWithTheAreaUpTo640x480AndWithTheSideBeyond) {
  EXPECT_DOUBLE_EQ(resolutionScale({320, 240}), 1.0);
  EXPECT_DOUBLE_EQ(resolutionScale({1280, 960}), 4.0);
  EXPECT_DOUBLE_EQ(countScale({320, 240}), 1.0);
  EXPECT_DOUBLE_EQ(countScale({160, 120}), 0.25);
  EXPECT_DOUBLE_EQ(countScale({640, 480}), 4.0);
  // Beyond 640x480: 4 times the side ratio to 640x480 (continuous at 640x480).
  EXPECT_DOUBLE_EQ(countScale({1280, 960}), 8.0);
  EXPECT_NEAR(countScale({1280, 720}), 2.0 * std::sqrt(12.0), 1e-12);
  EXPECT_NEAR(countScale({1920, 1080}), 2.0 * std::sqrt(27.0), 1e-12);
  EXPECT_NEAR(countScale({641, 480}), 4.0 * std::sqrt(641.0 / 640.0), 1e-12);
  // The corner and wide-baseline counts follow it.
  const CornerParams corners;
  EXPECT_EQ(corners.countFor({640, 480}), 4 * 55);
  EXPECT_EQ(corners.countFor({1280, 720}), static_cast<int>(std::lround(55 * 2 * std::sqrt(12.0))));
  const WideBaselineParams wide;
  EXPECT_EQ(wide.referenceCornersFor({1920, 1080}),
            static_cast<int>(std::lround(50 * 2 * std::sqrt(27.0))));
}
