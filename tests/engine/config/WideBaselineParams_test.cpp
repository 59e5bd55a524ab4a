#include "engine/config/WideBaselineParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(WideBaselineParams, RoundTrip) {
  WideBaselineParams in;
  in.dx = 7;
  in.dy = 4;
  in.halfWindow = 6;
  in.minScore = 0.5;
  in.referenceCornersAt320x240 = 33;
  in.frameToFrameCornersAt320x240 = 21;
  in.frameCornerQuality = 0.002;
  in.seedSearchAt320x240 = 17;
  WideBaselineParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.dx, 7);
  EXPECT_EQ(out.dy, 4);
  EXPECT_EQ(out.halfWindow, 6);
  EXPECT_DOUBLE_EQ(out.minScore, 0.5);
  EXPECT_EQ(out.referenceCornersAt320x240, 33);
  EXPECT_EQ(out.frameToFrameCornersAt320x240, 21);
  EXPECT_DOUBLE_EQ(out.frameCornerQuality, 0.002);
  EXPECT_EQ(out.seedSearchAt320x240, 17);
}

TEST(WideBaselineParams, CountsScaleWithTheImageArea) {
  WideBaselineParams p;
  p.referenceCornersAt320x240 = 50;
  p.frameToFrameCornersAt320x240 = 40;
  EXPECT_EQ(p.referenceCornersFor({320, 240}), 50);
  EXPECT_EQ(p.referenceCornersFor({640, 480}), 200);
  EXPECT_EQ(p.frameToFrameCornersFor({640, 480}), 160);
  p.referenceCornersAt320x240 = 0;  // no cap
  EXPECT_EQ(p.referenceCornersFor({640, 480}), 0);
}

TEST(WideBaselineParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(WideBaselineParams&)>>> cases = {
      {"wide_baseline.dx", [](WideBaselineParams& p) { p.dx = -1; }},
      {"wide_baseline.dy", [](WideBaselineParams& p) { p.dy = -1; }},
      {"wide_baseline.n", [](WideBaselineParams& p) { p.halfWindow = 0; }},
      {"wide_baseline.min_score", [&](WideBaselineParams& p) { p.minScore = nan; }},
      {"wide_baseline.affine_neighbours", [](WideBaselineParams& p) { p.affineNeighbours = 2; }},
      {"wide_baseline.reference_corners",
       [](WideBaselineParams& p) { p.referenceCornersAt320x240 = -1; }},
      {"wide_baseline.frame_to_frame_corners",
       [](WideBaselineParams& p) { p.frameToFrameCornersAt320x240 = 4; }},
      {"wide_baseline.frame_corner_quality",
       [&](WideBaselineParams& p) { p.frameCornerQuality = nan; }},
      {"wide_baseline.frame_corner_quality",
       [](WideBaselineParams& p) { p.frameCornerQuality = 0.0; }},
      {"wide_baseline.seed_search", [](WideBaselineParams& p) { p.seedSearchAt320x240 = 0; }},
  };
  for (const auto& [field, mutate] : cases) {
    WideBaselineParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}
