#include "engine/config/PoseParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(PoseParams, DefaultsAndRoundTrip) {
  PoseParams in;
  EXPECT_EQ(in.estimator, PoseEstimatorKind::Regularised);
  EXPECT_DOUBLE_EQ(in.alpha, 1.0);
  EXPECT_EQ(in.arOrder, 1);
  in.estimator = PoseEstimatorKind::Standard;
  in.alpha = 2.5;
  in.arOrder = 2;
  in.translationSigma = 0.004;
  in.rotationSigma = 0.003;
  in.motionModelFile = "model.yml";
  EXPECT_DOUBLE_EQ(in.rollingShutterReadout, 0.0);  // global shutter unless told
  in.rollingShutterReadout = 0.6;
  EXPECT_FALSE(in.estimateRollingShutter);  // off unless asked for (real clips: README)
  EXPECT_DOUBLE_EQ(in.mapPointSdScale, 0.5);
  in.estimateRollingShutter = true;
  in.mapPointSdScale = 0.0;
  EXPECT_DOUBLE_EQ(in.reliabilityPriorObservations, 2.0);  // learned reliability on (README)
  in.reliabilityPriorObservations = 0.0;
  EXPECT_DOUBLE_EQ(in.predictedErrorScale, 1.7);  // measured on the real clips
  EXPECT_DOUBLE_EQ(in.maxPredictedErrorPx, 2.0);  // chosen on the real clips
  in.predictedErrorScale = 1.5;
  in.maxPredictedErrorPx = 0.0;
  EXPECT_EQ(in.verifyUnsureEveryFrames, 15);  // ~3 ms per frame of 43-60 ms searches (README)
  in.verifyUnsureEveryFrames = 1;
  PoseParams out;
  roundTrip(in, out);
  EXPECT_EQ(out.estimator, PoseEstimatorKind::Standard);
  EXPECT_DOUBLE_EQ(out.alpha, 2.5);
  EXPECT_EQ(out.arOrder, 2);
  EXPECT_DOUBLE_EQ(out.translationSigma, 0.004);
  EXPECT_DOUBLE_EQ(out.rotationSigma, 0.003);
  EXPECT_EQ(out.motionModelFile, "model.yml");
  EXPECT_DOUBLE_EQ(out.rollingShutterReadout, 0.6);
  EXPECT_TRUE(out.estimateRollingShutter);
  EXPECT_DOUBLE_EQ(out.mapPointSdScale, 0.0);
  EXPECT_DOUBLE_EQ(out.reliabilityPriorObservations, 0.0);
  EXPECT_DOUBLE_EQ(out.predictedErrorScale, 1.5);
  EXPECT_DOUBLE_EQ(out.maxPredictedErrorPx, 0.0);
  EXPECT_EQ(out.verifyUnsureEveryFrames, 1);
}

TEST(PoseParams, EveryBadFieldIsNamed) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<std::pair<std::string, std::function<void(PoseParams&)>>> cases = {
      {"pose.alpha", [&](PoseParams& p) { p.alpha = nan; }},
      {"pose.ar_order", [](PoseParams& p) { p.arOrder = 0; }},
      {"pose.translation_sigma", [](PoseParams& p) { p.translationSigma = 0; }},
      {"pose.translation_sigma", [&](PoseParams& p) { p.translationSigma = nan; }},
      {"pose.alpha", [](PoseParams& p) { p.alpha = std::numeric_limits<double>::infinity(); }},
      {"pose.rotation_sigma", [&](PoseParams& p) { p.rotationSigma = nan; }},
      {"pose.rolling_shutter_readout", [](PoseParams& p) { p.rollingShutterReadout = -0.1; }},
      {"pose.rolling_shutter_readout", [](PoseParams& p) { p.rollingShutterReadout = 1.5; }},
      {"pose.reliability_prior_observations",
       [](PoseParams& p) { p.reliabilityPriorObservations = -1.0; }},
      {"pose.reliability_prior_observations",
       [&](PoseParams& p) { p.reliabilityPriorObservations = nan; }},
      {"pose.predicted_error_scale", [](PoseParams& p) { p.predictedErrorScale = 0.0; }},
      {"pose.predicted_error_scale", [&](PoseParams& p) { p.predictedErrorScale = nan; }},
      {"pose.max_predicted_error_px", [](PoseParams& p) { p.maxPredictedErrorPx = -1.0; }},
      {"pose.max_predicted_error_px", [&](PoseParams& p) { p.maxPredictedErrorPx = nan; }},
      {"pose.verify_unsure_every_frames", [](PoseParams& p) { p.verifyUnsureEveryFrames = 0; }},
  };
  for (const auto& [field, mutate] : cases) {
    PoseParams p;
    mutate(p);
    EXPECT_NE(errorMessage([&] { p.check(); }).find(field), std::string::npos) << field;
  }
  EXPECT_NE(errorMessage([] { parsePoseEstimatorKind("kalman"); }).find("pose.estimator"),
            std::string::npos);
}
