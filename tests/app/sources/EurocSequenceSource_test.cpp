// EurocSequenceSource: cam0 frames with their ns timestamps in seconds, the sensor.yaml camera,
// from the sequence root, mav0 or the camera folder; bad layouts named.
#include "app/sources/EurocSequenceSource.hpp"

#include <gtest/gtest.h>

#include "DatasetFixtures.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(EurocSequenceSource, ReadsFramesTimestampsAndTheCamera) {
  const auto dir = test::freshTempDir("EurocSequenceSource_ok");
  Eigen::Matrix3d K;
  K << 458.654, 0, 367.215, 0, 457.296, 248.375, 0, 0, 1;
  const PinholeCamera camera(K, {752, 480}, {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05});
  const RigidPose tbs(Eigen::Quaterniond(0.7, 0.1, -0.7, 0.1).normalized(),
                      Eigen::Vector3d(-0.02, -0.06, 0.01));
  std::vector<cv::Mat> images;
  std::vector<long long> ns;
  for (int k = 0; k < 3; ++k) {
    images.emplace_back(480, 752, CV_8UC1, cv::Scalar(40 + k));
    ns.push_back(1403636579763555584LL + k * 50000000LL);
  }
  test::writeEurocSequence(dir, images, ns, camera, tbs, {});
  for (const auto& where : {dir, dir / "mav0", dir / "mav0" / "cam0"}) {
    EurocSequenceSource source(where);
    ASSERT_EQ(source.frameCount(), 3);
    EXPECT_NEAR(source.fps(), 20.0, 1e-3);
    EXPECT_EQ(source.camera().imageSize(), cv::Size(752, 480));
    EXPECT_DOUBLE_EQ(source.camera().fx(), 458.654);
    EXPECT_DOUBLE_EQ(source.camera().cy(), 248.375);
    EXPECT_DOUBLE_EQ(source.camera().distortion()[1], 0.07395907);
    EXPECT_LT(RigidPose::rotationDistance(source.dataset().sensorToBody, tbs), 1e-12);
    for (int k = 0; k < 3; ++k) {
      const auto frame = source.next();
      ASSERT_TRUE(frame);
      // ns -> s in a double near 1.4e9 s: within 2.4e-7 s.
      EXPECT_NEAR(frame->timestamp, ns[static_cast<std::size_t>(k)] * 1e-9, 3e-7);
      EXPECT_EQ(frame->image.type(), CV_8UC3);
      EXPECT_EQ(frame->image.at<cv::Vec3b>(0, 0)[2], 40 + k);
    }
  }
}

TEST(EurocSequenceSource, MissingLayoutIsAClearError) {
  const auto dir = test::freshTempDir("EurocSequenceSource_bad");
  try {
    EurocSequenceSource source(dir);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("expected DIR/mav0/cam0, DIR/cam0 or a camera folder"),
              std::string::npos)
        << e.what();
  }
}
