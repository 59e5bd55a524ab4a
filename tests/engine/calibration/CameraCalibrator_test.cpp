#include "engine/calibration/CameraCalibrator.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "engine/calibration/CalibrationInput.hpp"
#include "engine/calibration/SyntheticBoardViews.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

const cv::Size kSize = test::kBoardViewSize;

void addSyntheticViews(CameraCalibrator& calibrator, const CalibrationBoard& board) {
  const int pps = 64;
  const cv::Mat texture = test::chessboardTexture(board, pps);
  int i = 0;
  for (const RigidPose& pose : test::variedBoardPoses(board)) {
    // Every inner corner must be in the image, or the pose list is wrong (not the calibrator).
    for (const cv::Point3f& c : board.allCornerPositions()) {
      const Eigen::Vector3d X = pose * Eigen::Vector3d(c.x, c.y, c.z);
      const Eigen::Vector3d p = test::boardViewK() * X;
      ASSERT_GT(p.x() / p.z(), 5.0);
      ASSERT_LT(p.x() / p.z(), kSize.width - 6.0);
      ASSERT_GT(p.y() / p.z(), 5.0);
      ASSERT_LT(p.y() / p.z(), kSize.height - 6.0);
    }
    const cv::Mat img =
        test::renderBoardView(board, texture, pps, test::boardViewK(), kSize, pose, i);
    EXPECT_TRUE(calibrator.addImage(img, "view" + std::to_string(i))) << "view " << i;
    ++i;
  }
}

}  // namespace

TEST(CameraCalibrator, RecoversIntrinsicsFromSyntheticViews) {
  const CalibrationBoard board = CalibrationBoard::parse("chessboard:9x6:0.025");
  // The renderer has no lens distortion. With p1, p2 free, 15 views leave the tangential terms
  // and the principal point entangled (measured: cy off by 1.25 px = 0.53%), so they are fixed.
  CalibrationParams params;
  params.zeroTangent = true;
  CameraCalibrator calibrator(board, params);
  addSyntheticViews(calibrator, board);
  calibrator.addImage(cv::Mat(kSize, CV_8UC1, cv::Scalar(90)), "blank");
  const CalibrationResult r = calibrator.calibrate();
  EXPECT_EQ(r.views.size(), 15u);
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_EQ(r.rejected[0], "blank");
  EXPECT_EQ(r.imagesExamined, 16u);
  // The bar: fx, fy, cx, cy within 0.5% of the rendering camera.
  test::expectIntrinsicsNear(r.camera, test::boardViewK(), 0.005);
  // Rendered corners are exact up to interpolation and 2-grey-level noise: well under 0.2 px.
  EXPECT_LT(r.rmsPx, 0.2);
  for (const CalibrationViewError& v : r.views) {
    EXPECT_EQ(v.corners, 54);
    EXPECT_LT(v.rmsPx, 0.3) << v.label;
  }
  std::printf("synthetic: fx %.3f fy %.3f cx %.3f cy %.3f rms %.4f px\n", r.camera.fx(),
              r.camera.fy(), r.camera.cx(), r.camera.cy(), r.rmsPx);
}

TEST(CameraCalibrator, ThinsManyViewsToASpreadSubset) {
  const CalibrationBoard board = CalibrationBoard::parse("chessboard:9x6:0.025");
  CalibrationParams params;
  params.maxViews = 6;
  CameraCalibrator calibrator(board, params);
  addSyntheticViews(calibrator, board);
  const CalibrationResult r = calibrator.calibrate();
  EXPECT_EQ(r.viewsFound, 15u);
  ASSERT_EQ(r.views.size(), 6u);
  // The frontal view is the largest board and is picked first; the strongly tilted views differ
  // most from it, so at least one of the 35-degree tilts is among the six.
  bool hasTilted = false;
  for (const auto& v : r.views) hasTilted |= (v.label == "view1" || v.label == "view2");
  EXPECT_TRUE(hasTilted);
}

TEST(CameraCalibrator, ExplainsMissingOrTooFewViews) {
  const CalibrationBoard board = CalibrationBoard::parse("chessboard:9x6:0.025");
  CameraCalibrator none(board);
  none.addImage(cv::Mat(kSize, CV_8UC1, cv::Scalar(0)), "dark");
  try {
    none.calibrate();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("none of the 1 images"), std::string::npos);
  }
  CameraCalibrator few(board);
  const cv::Mat texture = test::chessboardTexture(board, 64);
  few.addImage(test::renderBoardView(board, texture, 64, test::boardViewK(), kSize,
                                     test::variedBoardPoses(board)[0], 1),
               "one");
  EXPECT_THROW(few.addImage(cv::Mat(cv::Size(320, 240), CV_8UC1), "small"), Error);
  try {
    few.calibrate();
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("only 1 of"), std::string::npos);
  }
  CalibrationParams bad;
  bad.maxViews = 2;
  EXPECT_THROW(CameraCalibrator(board, bad), Error);
}

TEST(CameraCalibrator, MatchesOpenCvSampleCalibrationOnRealImages) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data is absent";
  const auto dir = *data / "chessboard-calib";
  CalibrationParams params;
  params.fixAspectRatio = true;  // as OpenCV's sample did (flags: 2)
  CameraCalibrator calibrator(CalibrationBoard::parse("chessboard:9x6:0.025"), params);
  CalibrationInput input((dir / "left*.jpg").string());
  cv::Mat img;
  std::string label;
  while (input.next(img, label)) calibrator.addImage(img, label);
  const CalibrationResult r = calibrator.calibrate();
  const PinholeCamera ref = PinholeCamera::load(dir / "left_intrinsics.yml");
  std::printf(
      "real left*.jpg: %zu views, fx %.3f fy %.3f cx %.3f cy %.3f rms %.4f px "
      "(OpenCV sample: fx %.3f cx %.3f cy %.3f rms 0.393)\n",
      r.views.size(), r.camera.fx(), r.camera.fy(), r.camera.cx(), r.camera.cy(), r.rmsPx, ref.fx(),
      ref.cx(), ref.cy());
  EXPECT_EQ(r.views.size(), 13u);
  // Same images, same model, different corner detector (SB vs classic): the sample's own result
  // is itself uncertain by a few pixels, so 1% on f and 2% of the width on the principal point.
  EXPECT_NEAR(r.camera.fx(), ref.fx(), 0.01 * ref.fx());
  EXPECT_NEAR(r.camera.cx(), ref.cx(), 0.02 * 640);
  EXPECT_NEAR(r.camera.cy(), ref.cy(), 0.02 * 640);
  EXPECT_LT(r.rmsPx, 0.5);
}
