// The recovery's cost calibration: the fit finds known coefficients exactly, keeps them
// non-negative, and the samples of a real recovery carry counted work and a measured cost.
#include "app/research/relocalisation/RecoveryCostCalibration.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "engine/core/Error.hpp"
#include "engine/relocalisation/ReferenceKeypointBuilder.hpp"
#include "engine/tracking/PlaneMultiWorld.hpp"

namespace reftrack::app {
namespace {

RecoveryWork work(double start, double seeded, double repeated, double detected, double comparisons,
                  int searches) {
  RecoveryWork w;
  w.startPassMegapixels = start;
  w.seededPassMegapixels = seeded;
  w.repeatedPassMegapixels = repeated;
  w.keypoints.detectedMegapixels = detected;
  w.keypoints.comparisonsMillions = comparisons;
  w.keypoints.poseSearches = searches;
  return w;
}

// Recoveries of varied make-up whose cost a known model gives exactly: the fit returns that model
// (to rounding) and agrees with every sample.
TEST(RecoveryCostCalibration, TheFitFindsTheModelThatMadeTheCosts) {
  RecoveryCostModel truth;
  truth.msPerStartPassMegapixel = 9.0;
  truth.msPerSeededPassMegapixel = 13.0;
  truth.msPerRepeatedPassMegapixel = 6.0;
  truth.msPerDetectedMegapixel = 250.0;
  truth.msPerMillionComparisons = 40.0;
  truth.msPerPoseSearch = 3.0;
  std::vector<RecoverySample> samples;
  for (int i = 0; i < 40; ++i) {
    const RecoveryWork w = work(0.36 * (1 + i % 2), 0.36 * (i % 3), 0.36 * (i % 4 == 0),
                                0.18 * (i % 5), 0.05 * (i % 7), i % 3 == 1);
    samples.push_back({i % 2 ? "cold" : "shuffled", i, w, truth.ms(w)});
  }
  const RecoveryCostModel fitted = fitRecoveryCostModel(samples);
  EXPECT_NEAR(fitted.msPerStartPassMegapixel, 9.0, 1e-6);
  EXPECT_NEAR(fitted.msPerSeededPassMegapixel, 13.0, 1e-6);
  EXPECT_NEAR(fitted.msPerRepeatedPassMegapixel, 6.0, 1e-6);
  EXPECT_NEAR(fitted.msPerDetectedMegapixel, 250.0, 1e-6);
  EXPECT_NEAR(fitted.msPerMillionComparisons, 40.0, 1e-6);
  EXPECT_NEAR(fitted.msPerPoseSearch, 3.0, 1e-6);
  const CostModelAgreement a = agreement(fitted, samples);
  EXPECT_EQ(a.samples, 40);
  EXPECT_NEAR(a.sumRatio, 1.0, 1e-9);
  EXPECT_NEAR(a.p10Ratio, 1.0, 1e-9);
  EXPECT_NEAR(a.p90Ratio, 1.0, 1e-9);
}

// A term that only lowers the cost (its unconstrained coefficient would be negative) is held at
// zero; no samples is a clear error.
TEST(RecoveryCostCalibration, CoefficientsStayNonNegative) {
  std::vector<RecoverySample> samples;
  for (int i = 1; i <= 20; ++i) {
    const RecoveryWork w = work(0.36, 0.0, 0.0, 0.0, 0.01 * i, 0);
    samples.push_back({"cold", i, w, 10.0 - 0.2 * i});  // more comparisons, less time
  }
  const RecoveryCostModel fitted = fitRecoveryCostModel(samples);
  EXPECT_GE(fitted.msPerMillionComparisons, 0.0);
  EXPECT_GT(fitted.msPerStartPassMegapixel, 0.0);
  EXPECT_THROW(fitRecoveryCostModel({}), Error);
}

// Frames of an unrelated texture after a tracked start: every one is recovered (the budget is
// lifted), with the work counted and a measured cost; the repeats give the same recoveries.
TEST(RecoveryCostCalibration, SamplesCarryTheCountedWorkOfEveryRecovery) {
  const test::PlaneMultiWorld world({-0.1, 0.1});
  MultiReferenceMap map = world.map();
  buildReferenceKeypoints(map, RelocalisationParams{});
  std::vector<cv::Mat> frames = {world.render(test::PlaneMultiWorld::cameraAlong(-0.1, 0), 1),
                                 test::texturedImage(world.size, 5),
                                 test::texturedImage(world.size, 6)};
  const std::vector<RecoverySample> samples =
      collectRecoverySamples(map, frames, TrackerParams{}, 1, 2);
  int cold = 0;
  for (const RecoverySample& s : samples) {
    cold += s.order == "cold" ? 1 : 0;
    EXPECT_GT(s.work.startPassMegapixels, 0.0) << s.order << " " << s.frame;
  }
  EXPECT_EQ(cold, 3);  // every frame a cold start
  int searched = 0;
  for (const RecoverySample& s : samples)
    searched += s.frame > 0 && s.work.keypoints.detectedMegapixels > 0.0 ? 1 : 0;
  EXPECT_GE(searched, 2);  // the textures are searched by the relocaliser
  EXPECT_THROW(collectRecoverySamples(map, frames, TrackerParams{}, 1, 0), Error);
}

}  // namespace
}  // namespace reftrack::app
