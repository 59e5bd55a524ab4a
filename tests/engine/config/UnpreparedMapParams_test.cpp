#include "engine/config/UnpreparedMapParams.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(UnpreparedMapParams, DefaultsAreValid) {
  UnpreparedMapParams p;
  p.check();
  EXPECT_EQ(p.keypoints, "sift");
  EXPECT_DOUBLE_EQ(p.minParallaxDeg, 1.5);
  EXPECT_DOUBLE_EQ(p.maxRotationShare, 0.8);
}

TEST(UnpreparedMapParams, RoundTrip) {
  UnpreparedMapParams in;
  in.keypoints = "akaze";
  in.maxKeypoints = 2500;
  in.ratio = 0.75;
  in.minKeypoints = 120;
  in.minMatches = 70;
  in.ransacThresholdPx = 1.5;
  in.minInliers = 50;
  in.maxRotationShare = 0.7;
  in.minParallaxDeg = 2.5;
  in.bootstrapEpipolarDistancePx = 4.0;
  in.bootstrapReprojectionErrorPx = 2.5;
  in.refinementRounds = 3;
  UnpreparedMapParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.keypoints, "akaze");
  EXPECT_EQ(out.maxKeypoints, 2500);
  EXPECT_DOUBLE_EQ(out.ratio, 0.75);
  EXPECT_EQ(out.minKeypoints, 120);
  EXPECT_EQ(out.minMatches, 70);
  EXPECT_DOUBLE_EQ(out.ransacThresholdPx, 1.5);
  EXPECT_EQ(out.minInliers, 50);
  EXPECT_DOUBLE_EQ(out.maxRotationShare, 0.7);
  EXPECT_DOUBLE_EQ(out.minParallaxDeg, 2.5);
  EXPECT_DOUBLE_EQ(out.bootstrapEpipolarDistancePx, 4.0);
  EXPECT_DOUBLE_EQ(out.bootstrapReprojectionErrorPx, 2.5);
  EXPECT_EQ(out.refinementRounds, 3);
}

TEST(UnpreparedMapParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(UnpreparedMapParams&)>>> cases = {
      {"unprepared.keypoints", [](UnpreparedMapParams& p) { p.keypoints = "surf"; }},
      {"unprepared.max_keypoints", [](UnpreparedMapParams& p) { p.maxKeypoints = 10; }},
      {"unprepared.ratio", [&](UnpreparedMapParams& p) { p.ratio = nan; }},
      {"unprepared.min_keypoints", [](UnpreparedMapParams& p) { p.minKeypoints = 0; }},
      {"unprepared.min_matches", [](UnpreparedMapParams& p) { p.minMatches = 7; }},
      {"unprepared.ransac_threshold_px", [](UnpreparedMapParams& p) { p.ransacThresholdPx = 0; }},
      {"unprepared.min_inliers", [](UnpreparedMapParams& p) { p.minInliers = -1; }},
      {"unprepared.max_rotation_share", [](UnpreparedMapParams& p) { p.maxRotationShare = 1.5; }},
      {"unprepared.min_parallax_deg",
       [](UnpreparedMapParams& p) { p.minParallaxDeg = std::numeric_limits<double>::infinity(); }},
      {"unprepared.bootstrap_epipolar_distance_px",
       [](UnpreparedMapParams& p) { p.bootstrapEpipolarDistancePx = -2; }},
      {"unprepared.bootstrap_reprojection_error_px",
       [](UnpreparedMapParams& p) { p.bootstrapReprojectionErrorPx = 0; }},
      {"unprepared.refinement_rounds", [](UnpreparedMapParams& p) { p.refinementRounds = 0; }},
  };
  for (const auto& [field, mutate] : cases) {
    UnpreparedMapParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}

TEST(UnpreparedMapParams, UnknownKeyNamesTheNearestOne) {
  const YamlNode fs = parseYaml("unprepared: { min_paralax_deg: 2 }\n");
  UnpreparedMapParams p;
  const std::string message = errorMessage([&] { p.read(fs["unprepared"]); });
  EXPECT_NE(message.find("unprepared.min_parallax_deg"), std::string::npos) << message;
}
