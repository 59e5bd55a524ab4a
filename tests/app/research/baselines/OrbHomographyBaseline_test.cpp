#include "app/research/baselines/OrbHomographyBaseline.hpp"

#include <gtest/gtest.h>

#include "app/research/homography/HomographyGroundTruth.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(OrbHomographyBaseline, RegistersAWarpedTexturedImage) {
  const cv::Size size(640, 480);
  const cv::Mat world = test::texturedImage(size, 31);
  const OrbHomographyBaseline baseline(world);
  const cv::Matx33d truth(0.98, -0.05, 20, 0.04, 0.99, -12, 1e-5, -2e-5, 1);
  const OrbHomographyResult r = baseline.track(test::withNoise(test::warpedBy(world, truth), 2, 3));
  ASSERT_TRUE(r.tracked) << r.inliers << " of " << r.matches;
  EXPECT_GT(r.inliers, 50);
  // ORB keypoints are pixel-quantised on a pyramid: a few hundred inliers average that to well
  // under 2 px at the frame corners (the worst, extrapolated place).
  EXPECT_LT(frameCornerError(r.H, truth, size), 2.0);
}

TEST(OrbHomographyBaseline, FailsOnUnrelatedImagesAndBadInput) {
  const cv::Size size(320, 240);
  const OrbHomographyBaseline baseline(test::texturedImage(size, 32));
  EXPECT_FALSE(baseline.track(test::texturedImage(size, 33)).tracked);
  EXPECT_THROW(baseline.track(test::texturedImage({640, 480}, 33)), Error);
  EXPECT_THROW(OrbHomographyBaseline(cv::Mat()), Error);
  EXPECT_THROW(OrbHomographyBaseline(cv::Mat(240, 320, CV_8UC1, cv::Scalar(90))), Error);
}
