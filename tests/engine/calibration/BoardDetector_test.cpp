#include "engine/calibration/BoardDetector.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "engine/calibration/SyntheticBoardViews.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

TEST(BoardDetector, FindsRenderedChessboardCornersToSubPixel) {
  const CalibrationBoard board = CalibrationBoard::parse("chessboard:9x6:0.025");
  Eigen::Matrix3d K;
  K << 600, 0, 319.5, 0, 600, 239.5, 0, 0, 1;
  const RigidPose pose = test::boardPose(board, 20, -15, 10, 0.01, 0.0, 0.5);
  const cv::Mat img =
      test::renderBoardView(board, test::chessboardTexture(board, 64), 64, K, {640, 480}, pose, 3);
  const auto obs = BoardDetector(board).detect(img);
  ASSERT_TRUE(obs.has_value());
  ASSERT_EQ(obs->imagePoints.size(), 54u);
  // The board may be reported from either end; compare each corner with the nearest projection.
  double worst = 0.0;
  for (std::size_t i = 0; i < 54; ++i) {
    const cv::Point3f c = obs->objectPoints[i];
    const Eigen::Vector3d p = K * (pose * Eigen::Vector3d(c.x, c.y, c.z));
    const cv::Point2f mirrored = obs->imagePoints[53 - i];
    const double direct = cv::norm(obs->imagePoints[i] - cv::Point2f(p.x() / p.z(), p.y() / p.z()));
    const double flipped = cv::norm(mirrored - cv::Point2f(p.x() / p.z(), p.y() / p.z()));
    worst = std::max(worst, std::min(direct, flipped));
  }
  // Exact rendering with 2-grey-level noise: corners land within 0.25 px of the projection.
  EXPECT_LT(worst, 0.25);
}

TEST(BoardDetector, ReportsNothingOnABlankImageAndRejectsBadImages) {
  BoardDetector detector(CalibrationBoard::parse("chessboard:9x6:0.025"));
  EXPECT_FALSE(detector.detect(cv::Mat(480, 640, CV_8UC1, cv::Scalar(128))).has_value());
  EXPECT_THROW(detector.detect(cv::Mat()), Error);
  EXPECT_THROW(detector.detect(cv::Mat(10, 10, CV_32FC1)), Error);
}

TEST(BoardDetector, FindsCharucoCornersOnRealPhoto) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data is absent";
  const cv::Mat img = cv::imread((*data / "aruco-charuco/img_00.jpg").string());
  ASSERT_FALSE(img.empty());
  const CalibrationBoard board = CalibrationBoard::parse("charuco:DICT_6X6_250:5x7:0.04:0.02");
  const auto obs = BoardDetector(board).detect(img);
  ASSERT_TRUE(obs.has_value());
  // A 5x7 board has 24 inner corners; the photo shows the whole board.
  EXPECT_GE(obs->imagePoints.size(), 20u);
  EXPECT_EQ(obs->imagePoints.size(), obs->objectPoints.size());
}
