#include "engine/config/ReferenceSelectionParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(ReferenceSelectionParams, RoundTrip) {
  ReferenceSelectionParams in;
  in.angleWeight = 0.5;
  in.minSharedPoints = 12;
  in.switchMargin = 0.3;
  in.switchAfterFrames = 5;
  in.cachedTrackers = 2;
  in.reseedFrames = 7;
  ReferenceSelectionParams out;
  roundTrip(in, out);
  EXPECT_DOUBLE_EQ(out.angleWeight, 0.5);
  EXPECT_EQ(out.minSharedPoints, 12);
  EXPECT_DOUBLE_EQ(out.switchMargin, 0.3);
  EXPECT_EQ(out.switchAfterFrames, 5);
  EXPECT_EQ(out.cachedTrackers, 2);
  EXPECT_EQ(out.reseedFrames, 7);
}

TEST(ReferenceSelectionParams, MissingKeysKeepDefaults) {
  ReferenceSelectionParams p;
  const YamlNode fs = parseYaml("references:\n  switch_after_frames: 9\n");
  p.read(fs["references"]);
  EXPECT_EQ(p.switchAfterFrames, 9);
  EXPECT_EQ(p.minSharedPoints, ReferenceSelectionParams{}.minSharedPoints);
}

TEST(ReferenceSelectionParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(ReferenceSelectionParams&)>>> cases =
      {
          {"references.angle_weight", [&](ReferenceSelectionParams& p) { p.angleWeight = nan; }},
          {"references.angle_weight", [](ReferenceSelectionParams& p) { p.angleWeight = -1; }},
          {"references.min_shared_points",
           [](ReferenceSelectionParams& p) { p.minSharedPoints = 5; }},
          {"references.switch_margin", [](ReferenceSelectionParams& p) { p.switchMargin = 1.0; }},
          {"references.switch_after_frames",
           [](ReferenceSelectionParams& p) { p.switchAfterFrames = 0; }},
          {"references.cached_trackers", [](ReferenceSelectionParams& p) { p.cachedTrackers = 0; }},
          {"references.reseed_frames", [](ReferenceSelectionParams& p) { p.reseedFrames = -1; }},
      };
  for (const auto& [field, mutate] : cases) {
    ReferenceSelectionParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
  const YamlNode fs = parseYaml("references:\n  switch_margin: 2.0\n");
  ReferenceSelectionParams p;
  EXPECT_NE(errorMessage([&] { p.read(fs["references"]); }).find("references.switch_margin"),
            std::string::npos);
}
