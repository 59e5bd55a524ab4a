#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "app/commands/CommandTestSupport.hpp"
#include "engine/calibration/CalibrationBoard.hpp"
#include "engine/geometry/PinholeCamera.hpp"

using namespace reftrack;

TEST(CalibrateCommand, CalibratesFromAFolderOfRealImages) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data is absent";
  const auto dir = test::freshTempDir("CalibrateCommand_Real");
  const auto r = test::runReftrack("calibrate --board chessboard:9x6:0.025 --input '" +
                                       (*data / "chessboard-calib" / "left*.jpg").string() +
                                       "' --fix-aspect --out " + (dir / "camera.yml").string(),
                                   dir);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  EXPECT_NE(r.out.find("found in 13 of 13 images"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("left14.jpg"), std::string::npos) << r.out;
  const PinholeCamera cam = PinholeCamera::load(dir / "camera.yml");
  // OpenCV's own result for these images is fx = fy = 535.9 px; 1% (see CameraCalibrator_test).
  EXPECT_NEAR(cam.fx(), 535.9, 5.4);
  EXPECT_DOUBLE_EQ(cam.fx(), cam.fy());
}

TEST(CalibrateCommand, BadBoardIsAUsageErrorAndNoBoardARuntimeError) {
  const auto dir = test::freshTempDir("CalibrateCommand_Errors");
  EXPECT_EQ(test::runReftrack("calibrate --board chess:9x6 --input . --out c.yml", dir).exitCode,
            2);
  for (int i = 0; i < 3; ++i)
    cv::imwrite((dir / ("blank" + std::to_string(i) + ".png")).string(),
                cv::Mat(240, 320, CV_8UC1, cv::Scalar(128)));
  const auto r = test::runReftrack("calibrate --board chessboard:9x6:0.025 --input " +
                                       dir.string() + " --out " + (dir / "c.yml").string(),
                                   dir);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.err.find("found in none of the 3 images"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "c.yml"));
}
