#include "engine/geometry/PixelDistortion.hpp"

#include <gtest/gtest.h>

using namespace reftrack;

namespace {

PinholeCamera wideWebcam() {
  const PinholeCamera ideal = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  return PinholeCamera(ideal.K(), ideal.imageSize(), {-0.3, 0.0, 0.0, 0.0});
}

}  // namespace

TEST(PixelDistortion, MatchesProjectDistorted) {
  const PinholeCamera cam = wideWebcam();
  for (const Eigen::Vector3d& X :
       {Eigen::Vector3d(0.4, -0.3, 1.0), Eigen::Vector3d(-0.1, 0.2, 2.0)}) {
    const Eigen::Vector2d ideal = cam.project(X), expected = cam.projectDistorted(X);
    const cv::Point2f got = distortPixels(
        cam, {cv::Point2f(static_cast<float>(ideal.x()), static_cast<float>(ideal.y()))})[0];
    EXPECT_NEAR(got.x, expected.x(), 1e-3);
    EXPECT_NEAR(got.y, expected.y(), 1e-3);
  }
  // Without distortion the pixels come back unchanged.
  const PinholeCamera pinhole = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  EXPECT_EQ(distortPixels(pinhole, {{12.5f, 7.25f}})[0], cv::Point2f(12.5f, 7.25f));
}
