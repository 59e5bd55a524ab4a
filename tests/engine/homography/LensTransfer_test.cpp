#include "engine/homography/LensTransfer.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;

// A camera turning about its centre through a k1 = -0.3 lens: ray X is recorded at
// projectDistorted(X) in the reference and projectDistorted(R X) in the frame, and
// H = K R K^-1 between the undistorted images carries the one to the other (float precision:
// 1e-3 px).
TEST(LensTransfer, CarriesRecordedPixelsOfARotatingCamera) {
  const PinholeCamera ideal = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  const PinholeCamera camera(ideal.K(), ideal.imageSize(), {-0.3, 0.0, 0.0, 0.0});
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(0.12, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).matrix();
  const Eigen::Matrix3d He = camera.K() * R * camera.K().inverse();
  cv::Matx33d H;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) H(r, c) = He(r, c);
  std::vector<Eigen::Vector3d> rays = {
      {0.0, 0.0, 1.0}, {0.3, 0.2, 1.0}, {-0.35, -0.3, 1.0}, {0.25, -0.28, 1.0}};
  std::vector<cv::Point2d> reference;
  for (const Eigen::Vector3d& X : rays) {
    const Eigen::Vector2d p = camera.projectDistorted(X);
    reference.emplace_back(p.x(), p.y());
  }
  const std::vector<cv::Point2d> got = transferThroughLens(H, reference, camera);
  double worst = 0.0, worstPlain = 0.0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const Eigen::Vector2d expected = camera.projectDistorted(R * rays[i]);
    worst = std::max(worst, std::hypot(got[i].x - expected.x(), got[i].y - expected.y()));
    const cv::Point2d plain = transferPoint(H, reference[i]);
    worstPlain = std::max(worstPlain, std::hypot(plain.x - expected.x(), plain.y - expected.y()));
  }
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(worstPlain, 2.0);  // H applied to the recorded pixels misses: not a homography there
}

TEST(LensTransfer, NaNBehindTheCameraAndPlainWithoutDistortion) {
  const PinholeCamera pinhole = PinholeCamera::fromFieldOfView({640, 480}, 50.0);
  const cv::Matx33d H(1.1, 0.02, 5.0, -0.01, 0.95, -3.0, 1e-4, 2e-5, 1.0);
  const cv::Point2d p(100.0, 50.0);
  const cv::Point2d plain = transferPoint(H, p);
  const cv::Point2d got = transferThroughLens(H, {p}, pinhole)[0];
  EXPECT_NEAR(got.x, plain.x, 1e-3);
  EXPECT_NEAR(got.y, plain.y, 1e-3);
  const cv::Matx33d flip(1, 0, 0, 0, 1, 0, 0, 0, -1);
  EXPECT_TRUE(std::isnan(transferThroughLens(flip, {p}, pinhole)[0].x));
}
