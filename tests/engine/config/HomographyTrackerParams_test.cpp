#include "engine/config/HomographyTrackerParams.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "engine/config/ParamsTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::test;

TEST(HomographyTrackerParams, RoundTrip) {
  HomographyTrackerParams in;
  in.guidedSearchHalfSizePx = 4.5;
  in.frameToFramePrediction = false;
  in.reacquireWholeImage = false;
  in.reacquireCornerFactor = 2.5;
  in.frameCornerFactor = 1.5;
  in.reacquireCornerQuality = 0.003;
  in.reacquireMinDistancePx = 6;
  in.rotationModel = false;
  in.keypoints = KeypointLayer::Akaze;
  in.keypointFeatures = 700;
  in.keypointRatio = 0.7;
  in.keypointDetectScale = 0.5;
  in.keypointInlierThresholdPx = 2.5;
  in.refinePoints = 0;
  in.keypointTiltViews = 2;
  in.keypointConfidentInliers = 30;
  in.keypointSteepTiltViews = 3;
  in.keypointSteepTiltDeg = 62.5;
  in.keypointOneToOne = false;
  in.verify = false;
  in.verifyMinScore = 0.6;
  in.verifySearchPx = 5.0;
  in.verifyTolerancePx = 0.8;
  in.verifyMinFraction = 0.4;
  in.verifyMinSpread = 0.7;
  in.verifyMaxOffsetPx = 1.2;
  HomographyTrackerParams out;
  roundTrip(in, out);
  EXPECT_DOUBLE_EQ(out.guidedSearchHalfSizePx, 4.5);
  EXPECT_FALSE(out.frameToFramePrediction);
  EXPECT_FALSE(out.reacquireWholeImage);
  EXPECT_DOUBLE_EQ(out.reacquireCornerFactor, 2.5);
  EXPECT_DOUBLE_EQ(out.frameCornerFactor, 1.5);
  EXPECT_DOUBLE_EQ(out.reacquireCornerQuality, 0.003);
  EXPECT_DOUBLE_EQ(out.reacquireMinDistancePx, 6);
  EXPECT_FALSE(out.rotationModel);
  EXPECT_EQ(out.keypoints, KeypointLayer::Akaze);
  EXPECT_EQ(out.keypointFeatures, 700);
  EXPECT_DOUBLE_EQ(out.keypointRatio, 0.7);
  EXPECT_DOUBLE_EQ(out.keypointDetectScale, 0.5);
  EXPECT_DOUBLE_EQ(out.keypointInlierThresholdPx, 2.5);
  EXPECT_EQ(out.refinePoints, 0);
  EXPECT_EQ(out.keypointTiltViews, 2);
  EXPECT_EQ(out.keypointConfidentInliers, 30);
  EXPECT_EQ(out.keypointSteepTiltViews, 3);
  EXPECT_DOUBLE_EQ(out.keypointSteepTiltDeg, 62.5);
  EXPECT_FALSE(out.keypointOneToOne);
  EXPECT_FALSE(out.verify);
  EXPECT_DOUBLE_EQ(out.verifyMinScore, 0.6);
  EXPECT_DOUBLE_EQ(out.verifySearchPx, 5.0);
  EXPECT_DOUBLE_EQ(out.verifyTolerancePx, 0.8);
  EXPECT_DOUBLE_EQ(out.verifyMinFraction, 0.4);
  EXPECT_DOUBLE_EQ(out.verifyMinSpread, 0.7);
  EXPECT_DOUBLE_EQ(out.verifyMaxOffsetPx, 1.2);
}

TEST(HomographyTrackerParams, BadVerificationAndSteepTiltFieldsAreNamed) {
  HomographyTrackerParams p;
  p.keypointSteepTiltDeg = 85;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_steep_tilt_deg"),
            std::string::npos);
  p = {};
  p.keypointSteepTiltViews = 17;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_steep_tilt_views"),
            std::string::npos);
  p = {};
  p.verifyMinFraction = 1.5;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.verify_min_fraction"),
            std::string::npos);
  p = {};
  p.verifyMaxOffsetPx = 0;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.verify_max_offset_px"),
            std::string::npos);
  p = {};
  p.verifySearchPx = 0.5;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.verify_search_px"),
            std::string::npos);
}

TEST(HomographyTrackerParams, KeypointLayerNames) {
  for (KeypointLayer k :
       {KeypointLayer::None, KeypointLayer::Orb, KeypointLayer::Akaze, KeypointLayer::Sift})
    EXPECT_EQ(parseKeypointLayer(keypointLayerName(k)), k);
  EXPECT_NE(errorMessage([] { parseKeypointLayer("surf"); }).find("homography.keypoints"),
            std::string::npos);
  auto fs = parseYaml("homography:\n  keypoints: brisk\n");
  HomographyTrackerParams q;
  const std::string message = errorMessage([&] { q.read(fs["homography"]); });
  EXPECT_EQ(message.rfind("line 2: ", 0), 0u) << message;
  EXPECT_NE(message.find("'brisk'"), std::string::npos) << message;
}

TEST(HomographyTrackerParams, BadFieldIsNamed) {
  HomographyTrackerParams p;
  p.guidedSearchHalfSizePx = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.guided_search_half_size_px"),
            std::string::npos);
  p.guidedSearchHalfSizePx = 8;
  p.reacquireCornerFactor = 0.5;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.reacquire_corner_factor"),
            std::string::npos);
  p.reacquireCornerFactor = 3;
  p.frameCornerFactor = 20;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.frame_corner_factor"),
            std::string::npos);
  p.frameCornerFactor = 2;
  p.reacquireCornerQuality = 0;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.reacquire_corner_quality"),
            std::string::npos);
  p.reacquireCornerQuality = 1e-4;
  p.refinePoints = 3;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.refine_points"), std::string::npos);
  p.refinePoints = 150;
  p.keypointTiltViews = -1;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_tilt_views"),
            std::string::npos);
  p.keypointTiltViews = 4;
  p.reacquireMinDistancePx = std::numeric_limits<double>::infinity();
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.reacquire_min_distance_px"),
            std::string::npos);
  p.reacquireMinDistancePx = 4;
  p.keypointFeatures = 2;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_features"),
            std::string::npos);
  p.keypointFeatures = 1000;
  p.keypointRatio = 1.5;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_ratio"), std::string::npos);
  p.keypointRatio = 0.8;
  p.keypointDetectScale = 0;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_detect_scale"),
            std::string::npos);
  p.keypointDetectScale = 1;
  p.keypointInlierThresholdPx = -1;
  EXPECT_NE(errorMessage([&] { p.check(); }).find("homography.keypoint_inlier_threshold_px"),
            std::string::npos);
  auto fs = parseYaml("homography: { frame_to_frame_prediction: 3 }\n");
  HomographyTrackerParams q;
  EXPECT_EQ(errorMessage([&] { q.read(fs["homography"]); }),
            "line 1: parameter 'homography.frame_to_frame_prediction' must be true or false");
}
