#include "engine/config/RansacParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(RansacParams, DefaultsAreThePapers) {
  RansacParams p;
  p.check();
  EXPECT_EQ(p.maxIterations, 70);
  EXPECT_DOUBLE_EQ(p.earlyAcceptSupport, 0.75);
  EXPECT_EQ(p.earlyAcceptMinIterations, 15);
  EXPECT_DOUBLE_EQ(p.minSampleSpacingPx, 60);
  EXPECT_DOUBLE_EQ(p.minInlierRatio, 0.35);
  EXPECT_TRUE(p.refine);
  EXPECT_TRUE(p.progressiveSampling);  // not the paper's: ranked sampling within its 70 draws
}

TEST(RansacParams, RoundTrip) {
  RansacParams in;
  in.maxIterations = 200;
  in.inlierThresholdPx = 1.25;
  in.refine = false;
  in.seed = 9;
  in.progressiveSampling = false;
  RansacParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.maxIterations, 200);
  EXPECT_DOUBLE_EQ(out.inlierThresholdPx, 1.25);
  EXPECT_FALSE(out.refine);
  EXPECT_EQ(out.seed, 9);
  EXPECT_FALSE(out.progressiveSampling);
}

TEST(RansacParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(RansacParams&)>>> cases = {
      {"ransac.max_iterations", [](RansacParams& p) { p.maxIterations = 0; }},
      {"ransac.early_accept_support", [&](RansacParams& p) { p.earlyAcceptSupport = nan; }},
      {"ransac.early_accept_min_iterations",
       [](RansacParams& p) { p.earlyAcceptMinIterations = 0; }},
      {"ransac.min_sample_spacing_px", [](RansacParams& p) { p.minSampleSpacingPx = -5; }},
      {"ransac.min_determinant", [](RansacParams& p) { p.minDeterminant = 2; }},
      {"ransac.min_inlier_ratio", [](RansacParams& p) { p.minInlierRatio = 1.5; }},
      {"ransac.min_inliers", [](RansacParams& p) { p.minInliers = 3; }},
      {"ransac.inlier_threshold_px", [](RansacParams& p) { p.inlierThresholdPx = 0; }},
      {"ransac.seed", [](RansacParams& p) { p.seed = -1; }},
  };
  for (const auto& [field, mutate] : cases) {
    RansacParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}
