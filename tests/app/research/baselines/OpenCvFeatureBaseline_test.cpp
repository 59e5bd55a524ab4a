#include "app/research/baselines/OpenCvFeatureBaseline.hpp"

#include <gtest/gtest.h>

#include "app/research/homography/HomographyGroundTruth.hpp"
#include "engine/core/Error.hpp"
#include "engine/features/SyntheticImages.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(OpenCvFeatureBaseline, EachDetectorRegistersAWarpedTexturedImage) {
  const cv::Size size(640, 480);
  const cv::Mat world = test::texturedImage(size, 41);
  const cv::Matx33d truth = test::tiltedView(size, 25.0, 0.9, 40.0);
  const cv::Mat frame = test::withNoise(test::warpedBy(world, truth), 2, 4);
  for (const std::string name : {"sift", "akaze", "orb"}) {
    const OpenCvFeatureBaseline baseline(name, world);
    EXPECT_EQ(baseline.name(), name);
    const FeatureBaselineResult r = baseline.registerFrame(frame);
    ASSERT_TRUE(r.found) << name;
    EXPECT_GE(r.inliers, 8) << name;
    // Keypoint positions on a scale pyramid: a few pixels at the frame corners at worst.
    EXPECT_LT(frameCornerError(r.H, truth, size), 5.0) << name;
  }
}

TEST(OpenCvFeatureBaseline, RejectsBadInput) {
  const cv::Mat world = test::texturedImage({320, 240}, 42);
  EXPECT_THROW(OpenCvFeatureBaseline("surf", world), Error);
  EXPECT_THROW(OpenCvFeatureBaseline("sift", cv::Mat()), Error);
  EXPECT_THROW(OpenCvFeatureBaseline("orb", cv::Mat(240, 320, CV_8UC1, cv::Scalar(90))), Error);
  EXPECT_THROW(OpenCvFeatureBaseline("sift", world).registerFrame(cv::Mat()), Error);
}
