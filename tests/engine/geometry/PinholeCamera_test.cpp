#include "engine/geometry/PinholeCamera.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <opencv2/calib3d.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/PixelDistortion.hpp"

using namespace reftrack;

namespace {

std::filesystem::path writeFile(const std::filesystem::path& dir, const std::string& name,
                                const std::string& text) {
  std::ofstream(dir / name) << text;
  return dir / name;
}

std::string cameraYaml(const std::string& width, const std::string& K, const std::string& D) {
  return "%YAML:1.0\n---\nimage_width: " + width + "\nimage_height: 480\n" +
         "camera_matrix: !!opencv-matrix\n   rows: 3\n   cols: 3\n   dt: d\n   data: [" + K +
         "]\n" +
         "distortion_coefficients: !!opencv-matrix\n   rows: 5\n   cols: 1\n   dt: d\n   data: [" +
         D + "]\n";
}

std::string loadError(const std::filesystem::path& file) {
  return test::errorMessage([&] { PinholeCamera::load(file); });
}

}  // namespace

TEST(PinholeCamera, RoundTripsThroughYaml) {
  const auto dir = test::freshTempDir("PinholeCamera_RoundTrip");
  Eigen::Matrix3d K;
  K << 520.5, 0, 319.25, 0, 521.75, 240.5, 0, 0, 1;
  const PinholeCamera cam(K, {640, 480}, {0.1, -0.2, 0.001, -0.002, 0.05});
  cam.save(dir / "camera.yml");
  const PinholeCamera back = PinholeCamera::load(dir / "camera.yml");
  EXPECT_EQ(back.imageSize(), cam.imageSize());
  EXPECT_LT((back.K() - K).norm(), 1e-12);
  ASSERT_EQ(back.distortion().size(), 5u);
  for (size_t i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(back.distortion()[i], cam.distortion()[i]);
}

TEST(PinholeCamera, ReadsOpenCvCalibrationSampleOutput) {
  const auto data = test::sharedDataDir();
  if (!data) GTEST_SKIP() << "../shared/data not present: real-data check skipped";
  const PinholeCamera cam = PinholeCamera::load(*data / "chessboard-calib" / "left_intrinsics.yml");
  EXPECT_NEAR(cam.fx(), 535.916, 0.01);
  EXPECT_GT(cam.fx(), 100.0);
  EXPECT_EQ(cam.imageSize(), cv::Size(640, 480));
}

TEST(PinholeCamera, EachMalformedFileGivesItsOwnError) {
  const auto dir = test::freshTempDir("PinholeCamera_Malformed");
  const std::string goodK = "500, 0, 320, 0, 500, 240, 0, 0, 1", D = "0, 0, 0, 0, 0";
  EXPECT_EQ(loadError(writeFile(dir, "good.yml", cameraYaml("640", goodK, D))), "(no error)");
  EXPECT_NE(loadError(dir / "absent.yml").find("does not exist"), std::string::npos);
  EXPECT_NE(loadError(writeFile(dir, "garbage.yml", "%YAML:1.0\n---\n: : [\n")).find("camera file"),
            std::string::npos);
  EXPECT_NE(loadError(writeFile(dir, "nowidth.yml", "%YAML:1.0\n---\nimage_height: 480\n"))
                .find("missing key 'image_width'"),
            std::string::npos);
  EXPECT_NE(
      loadError(writeFile(dir, "zero.yml", cameraYaml("640", "0, 0, 320, 0, 500, 240, 0, 0, 1", D)))
          .find("fx must be positive"),
      std::string::npos);
  EXPECT_NE(
      loadError(writeFile(dir, "neg.yml", cameraYaml("640", "500, 0, 320, 0, -5, 240, 0, 0, 1", D)))
          .find("fy must be positive"),
      std::string::npos);
  EXPECT_NE(loadError(writeFile(dir, "nan.yml",
                                cameraYaml("640", "500, 0, .nan, 0, 500, 240, 0, 0, 1", D)))
                .find("NaN"),
            std::string::npos);
  EXPECT_NE(loadError(writeFile(dir, "nandist.yml", cameraYaml("640", goodK, "0, .nan, 0, 0, 0")))
                .find("distortion_coefficients contain NaN"),
            std::string::npos);
  EXPECT_NE(
      loadError(writeFile(dir, "size.yml", cameraYaml("-3", goodK, D))).find("must be positive"),
      std::string::npos);
  EXPECT_NE(
      loadError(writeFile(dir, "pp.yml", cameraYaml("640", "500, 0, 900, 0, 500, 240, 0, 0, 1", D)))
          .find("principal point"),
      std::string::npos);
}

TEST(PinholeCamera, ScaledCameraKeepsPixelCentreConvention) {
  const PinholeCamera cam = PinholeCamera::fromFieldOfView({320, 240}, 60.0);
  const PinholeCamera big = cam.scaled(2.0);
  const Eigen::Vector3d X(0.1, -0.05, 1.3);
  // A point at pixel p in the small image lies at (p + 0.5) * 2 - 0.5 in the doubled one.
  const Eigen::Vector2d p = cam.project(X), q = big.project(X);
  EXPECT_NEAR(q.x(), (p.x() + 0.5) * 2 - 0.5, 1e-9);
  EXPECT_NEAR(q.y(), (p.y() + 0.5) * 2 - 0.5, 1e-9);
  EXPECT_EQ(big.imageSize(), cv::Size(640, 480));
}

TEST(PinholeCamera, UndistortInvertsDistortedProjection) {
  Eigen::Matrix3d K;
  K << 500, 0, 320, 0, 500, 240, 0, 0, 1;
  const PinholeCamera cam(K, {640, 480}, {-0.25, 0.1, 0.001, 0.0005, 0.0});
  const Eigen::Vector3d X(0.3, -0.2, 1.0);
  const Eigen::Vector2d d = cam.projectDistorted(X);
  const auto u =
      cam.undistortPixels({cv::Point2f(static_cast<float>(d.x()), static_cast<float>(d.y()))});
  const Eigen::Vector2d ideal = cam.project(X);
  EXPECT_NEAR(u[0].x, ideal.x(), 0.01);
  EXPECT_NEAR(u[0].y, ideal.y(), 0.01);
}

namespace {

// A wide webcam: 640x480, 50 degrees horizontal, k1 = -0.3.
PinholeCamera wideWebcam() {
  const PinholeCamera ideal = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  return PinholeCamera(ideal.K(), ideal.imageSize(), {-0.3, 0.0, 0.0, 0.0});
}

}  // namespace

// At the image corners of a k1 = -0.3 lens OpenCV's default 5 iterations leave a large error (the
// fixed-point iteration contracts by only ~0.3 per step there); undistortPixels iterates until the
// point re-distorts to its pixel, so the round trip closes to float precision (1e-3 px).
TEST(PinholeCamera, UndistortIsExactAtTheCornersOfAStrongLens) {
  const PinholeCamera cam = wideWebcam();
  const std::vector<cv::Point2f> corners = {{-0.5f, -0.5f},   {639.5f, -0.5f}, {-0.5f, 479.5f},
                                            {639.5f, 479.5f}, {320.0f, 0.0f},  {0.0f, 240.0f}};
  const std::vector<cv::Point2f> ideal = cam.undistortPixels(corners);
  const std::vector<cv::Point2f> back = distortPixels(cam, ideal);
  std::vector<cv::Point2f> fiveIterations;
  cv::undistortPoints(corners, fiveIterations, cam.Kcv(), cam.distortion(), cv::noArray(),
                      cam.Kcv());
  double worst = 0.0, worstDefault = 0.0;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const cv::Point2d roundTrip = cv::Point2d(back[i]) - cv::Point2d(corners[i]);
    const cv::Point2d defaultGap = cv::Point2d(ideal[i]) - cv::Point2d(fiveIterations[i]);
    worst = std::max(worst, std::hypot(roundTrip.x, roundTrip.y));
    worstDefault = std::max(worstDefault, std::hypot(defaultGap.x, defaultGap.y));
  }
  std::cout << "round trip " << worst << " px; 5 iterations off by " << worstDefault << " px\n";
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(worstDefault, 0.05);  // the default would not do
}

TEST(PinholeCamera, UnknownKeysNameTheNearestAndTheYamlLineIsOptional) {
  const auto dir = test::freshTempDir("PinholeCamera_Strict");
  const std::string K = "500, 0, 320, 0, 500, 240, 0, 0, 1", D = "0.1, 0, 0, 0, 0";
  const std::string good = cameraYaml("640", K, D);
  // A misspelt distortion matrix would otherwise leave the lens undistorted in silence.
  std::string misspelt = good;
  misspelt.replace(misspelt.find("distortion_coefficients"), 23, "distortion_coefficents");
  EXPECT_NE(
      loadError(writeFile(dir, "key.yml", misspelt))
          .find("key.yml': line " +
                std::to_string(
                    1 + std::count(good.begin(), good.begin() + good.find("distortion_"), '\n')) +
                ": distortion_coefficents: unknown key — did you mean "
                "distortion_coefficients?"),
      std::string::npos);
  EXPECT_NE(loadError(writeFile(dir, "section.yml", good + "camera:\n  fx: 3\n"))
                .find("camera: unknown section — did you mean"),
            std::string::npos);
  // Without "%YAML:1.0" (hand-written) the file is read the same.
  const auto bare = writeFile(dir, "bare.yml", good.substr(good.find("image_width")));
  EXPECT_EQ(loadError(bare), "(no error)");
  EXPECT_DOUBLE_EQ(PinholeCamera::load(bare).distortion()[0], 0.1);
  // What OpenCV's calibration samples write beside the intrinsics is accepted.
  EXPECT_EQ(loadError(writeFile(dir, "sample.yml",
                                good + "calibration_time: \"today\"\nnframes: 13\n"
                                       "avg_reprojection_error: 0.39\nflags: 2\n")),
            "(no error)");
}
