#include "engine/config/CornerParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(CornerParams, DefaultsAreThePapersAndScaleWithImageArea) {
  CornerParams p;
  p.check();
  EXPECT_EQ(p.countFor({320, 240}), 55);   // paper: 50-60 corners per 320x240 image
  EXPECT_EQ(p.countFor({640, 480}), 220);  // four times the area
  EXPECT_DOUBLE_EQ(p.minDistanceFor({640, 480}), 2 * p.minDistancePx);
  EXPECT_EQ(p.contrastWindow, 15);
}

TEST(CornerParams, RoundTrip) {
  CornerParams in;
  in.countAt320x240 = 77;
  in.quality = 0.02;
  in.harrisK = 0.05;
  in.gridColumns = 6;
  in.fastThreshold = 12;
  in.detectAtPaperScale = false;
  CornerParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.countAt320x240, 77);
  EXPECT_DOUBLE_EQ(out.quality, 0.02);
  EXPECT_DOUBLE_EQ(out.harrisK, 0.05);
  EXPECT_EQ(out.gridColumns, 6);
  EXPECT_EQ(out.fastThreshold, 12);
  EXPECT_FALSE(out.detectAtPaperScale);
}

TEST(CornerParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(CornerParams&)>>> cases = {
      {"corners.count", [](CornerParams& p) { p.countAt320x240 = 0; }},
      {"corners.quality", [&](CornerParams& p) { p.quality = nan; }},
      {"corners.min_distance_px", [](CornerParams& p) { p.minDistancePx = -1; }},
      {"corners.harris_k", [](CornerParams& p) { p.harrisK = 0.5; }},
      {"corners.block_size", [](CornerParams& p) { p.blockSize = 1; }},
      {"corners.block_size", [](CornerParams& p) { p.blockSize = 4; }},
      {"corners.fast_threshold", [](CornerParams& p) { p.fastThreshold = 0; }},
      {"corners.grid_columns", [](CornerParams& p) { p.gridColumns = 0; }},
      {"corners.grid_rows", [](CornerParams& p) { p.gridRows = 0; }},
      {"corners.subpixel_half_window", [](CornerParams& p) { p.subPixelHalfWindow = 0; }},
      {"corners.contrast_window", [](CornerParams& p) { p.contrastWindow = 14; }},
  };
  for (const auto& [field, mutate] : cases) {
    CornerParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}

TEST(CornerParams, ReadRejectsWrongTypeNamingTheKey) {
  auto fs = parseYaml("corners: { count: many }\n");
  CornerParams p;
  EXPECT_NE(errorMessage([&] { p.read(fs["corners"]); }).find("corners.count"), std::string::npos);
}
