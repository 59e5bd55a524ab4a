#include "engine/config/MapExtensionParams.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(MapExtensionParams, DefaultsAreValid) {
  MapExtensionParams p;
  p.check();
  EXPECT_DOUBLE_EQ(p.maxDistanceMetres, 0.2);
  EXPECT_DOUBLE_EQ(p.maxAngleDeg, 15.0);
}

TEST(MapExtensionParams, RoundTrip) {
  MapExtensionParams in;
  in.maxDistanceMetres = 0.35;
  in.maxAngleDeg = 22.5;
  in.minInliers = 25;
  in.maxSupportSdPx = 0.2;
  in.matchReferences = 2;
  in.minOverlapPoints = 15;
  in.maxEpipolarDistancePx = 4.0;
  in.maxReprojectionErrorPx = 2.5;
  in.minNewPoints = 20;
  in.maxReferences = 10;
  MapExtensionParams out;
  roundTrip(in, out);
  EXPECT_DOUBLE_EQ(out.maxDistanceMetres, 0.35);
  EXPECT_DOUBLE_EQ(out.maxAngleDeg, 22.5);
  EXPECT_EQ(out.minInliers, 25);
  EXPECT_DOUBLE_EQ(out.maxSupportSdPx, 0.2);
  EXPECT_EQ(out.matchReferences, 2);
  EXPECT_EQ(out.minOverlapPoints, 15);
  EXPECT_DOUBLE_EQ(out.maxEpipolarDistancePx, 4.0);
  EXPECT_DOUBLE_EQ(out.maxReprojectionErrorPx, 2.5);
  EXPECT_EQ(out.minNewPoints, 20);
  EXPECT_EQ(out.maxReferences, 10);
}

TEST(MapExtensionParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(MapExtensionParams&)>>> cases = {
      {"extension.max_distance_m", [](MapExtensionParams& p) { p.maxDistanceMetres = 0; }},
      {"extension.max_angle_deg", [&](MapExtensionParams& p) { p.maxAngleDeg = nan; }},
      {"extension.min_inliers", [](MapExtensionParams& p) { p.minInliers = 5; }},
      {"extension.max_support_sd_px", [](MapExtensionParams& p) { p.maxSupportSdPx = -1; }},
      {"extension.match_references", [](MapExtensionParams& p) { p.matchReferences = 0; }},
      {"extension.min_overlap_points", [](MapExtensionParams& p) { p.minOverlapPoints = -1; }},
      {"extension.max_epipolar_distance_px",
       [](MapExtensionParams& p) { p.maxEpipolarDistancePx = 0; }},
      {"extension.max_reprojection_error_px",
       [](MapExtensionParams& p) { p.maxReprojectionErrorPx = 1e9; }},
      {"extension.min_new_points", [](MapExtensionParams& p) { p.minNewPoints = 0; }},
      {"extension.max_references", [](MapExtensionParams& p) { p.maxReferences = 1; }},
  };
  for (const auto& [field, mutate] : cases) {
    MapExtensionParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}

TEST(MapExtensionParams, WrongTypeInYamlIsNamed) {
  const YamlNode fs = parseYaml("extension: { max_angle_deg: wide }\n");
  MapExtensionParams p;
  EXPECT_EQ(errorMessage([&] { p.read(fs["extension"]); }),
            "line 1: parameter 'extension.max_angle_deg' must be a number");
}
