#include "engine/config/BundleAdjustmentParams.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(BundleAdjustmentParams, DefaultsAreValid) {
  BundleAdjustmentParams p;
  p.check();
  EXPECT_EQ(p.loss, "cauchy");
  EXPECT_DOUBLE_EQ(p.lossScalePx, 1.0);
}

TEST(BundleAdjustmentParams, RoundTrip) {
  BundleAdjustmentParams in;
  in.loss = "huber";
  in.lossScalePx = 2.5;
  in.outlierThresholdPx = 4.0;
  in.maxIterations = 30;
  in.minDeterminedPoints = 12;
  BundleAdjustmentParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.loss, "huber");
  EXPECT_DOUBLE_EQ(out.lossScalePx, 2.5);
  EXPECT_DOUBLE_EQ(out.outlierThresholdPx, 4.0);
  EXPECT_EQ(out.maxIterations, 30);
  EXPECT_EQ(out.minDeterminedPoints, 12);
}

TEST(BundleAdjustmentParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(BundleAdjustmentParams&)>>> cases = {
      {"bundle_adjustment.loss", [](BundleAdjustmentParams& p) { p.loss = "tukey"; }},
      {"bundle_adjustment.loss_scale_px", [&](BundleAdjustmentParams& p) { p.lossScalePx = nan; }},
      {"bundle_adjustment.outlier_threshold_px",
       [](BundleAdjustmentParams& p) { p.outlierThresholdPx = 0; }},
      {"bundle_adjustment.max_iterations", [](BundleAdjustmentParams& p) { p.maxIterations = 0; }},
      {"bundle_adjustment.min_determined_points",
       [](BundleAdjustmentParams& p) { p.minDeterminedPoints = 2; }},
  };
  for (const auto& [field, mutate] : cases) {
    BundleAdjustmentParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
}

TEST(BundleAdjustmentParams, WrongTypeInYamlIsNamed) {
  const YamlNode fs = parseYaml("# read by `extend`\nbundle_adjustment: { loss_scale_px: abc }\n");
  BundleAdjustmentParams p;
  EXPECT_EQ(errorMessage([&] { p.read(fs["bundle_adjustment"]); }),
            "line 2: parameter 'bundle_adjustment.loss_scale_px' must be a number");
}
