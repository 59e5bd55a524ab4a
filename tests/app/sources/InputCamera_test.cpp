// cameraFromInput: a euroc: input brings its sensor.yaml camera (and says so); others none.
#include "app/sources/InputCamera.hpp"

#include <gtest/gtest.h>

#include "DatasetFixtures.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(InputCamera, EurocInputsBringTheirCameraOthersNone) {
  const auto dir = test::freshTempDir("InputCamera");
  Eigen::Matrix3d K;
  K << 300, 0, 160.5, 0, 310, 120.25, 0, 0, 1;
  test::writeEurocSequence(dir, {cv::Mat(240, 320, CV_8UC1, cv::Scalar(1))}, {5},
                           PinholeCamera(K, {320, 240}, {0.1, -0.2, 0.001, 0.002}), RigidPose(),
                           {});
  testing::internal::CaptureStdout();
  const std::optional<PinholeCamera> c = cameraFromInput("euroc:" + dir.string());
  const std::string out = testing::internal::GetCapturedStdout();
  ASSERT_TRUE(c);
  EXPECT_EQ(c->K(), K);
  EXPECT_EQ(c->imageSize(), cv::Size(320, 240));
  EXPECT_EQ(c->distortion(), std::vector<double>({0.1, -0.2, 0.001, 0.002}));
  EXPECT_NE(out.find("camera: from " + (dir / "mav0" / "cam0" / "sensor.yaml").string() +
                     " (no --camera given)"),
            std::string::npos)
      << out;
  EXPECT_FALSE(cameraFromInput(dir.string()));
  EXPECT_FALSE(cameraFromInput("tum:" + dir.string()));
  EXPECT_FALSE(cameraFromInput("sim:handheld"));
  EXPECT_THROW(cameraFromInput("euroc:" + (dir / "mav0" / "cam0" / "data").string()), Error);
}
