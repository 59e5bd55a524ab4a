#include "app/research/homography/HomographyGroundTruth.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack::app;

namespace {

Eigen::Matrix3d intrinsics(double f, cv::Size size) {
  Eigen::Matrix3d K;
  K << f, 0, (size.width - 1) / 2.0, 0, f, (size.height - 1) / 2.0, 0, 0, 1;
  return K;
}

}  // namespace

TEST(HomographyGroundTruth, PanHomographyMovesTheCentreByFTanAngle) {
  const cv::Size size(320, 240);
  const Eigen::Matrix3d K = intrinsics(500, size);
  const double angle = 0.1;
  const cv::Matx33d H =
      rotationHomography(K, Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()).matrix());
  // The ray through the principal point turns by `angle` about y: it lands f tan(angle) away
  // (X_frame = R X_ref: a +y rotation turns the optical axis +z towards +x).
  const cv::Point2d c(K(0, 2), K(1, 2));
  const cv::Point2d q = reftrack::transferPoint(H, c);
  EXPECT_NEAR(q.x - c.x, 500 * std::tan(angle), 1e-9);
  EXPECT_NEAR(q.y - c.y, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(H(2, 2), 1.0);
}

TEST(HomographyGroundTruth, OverlapFallsWithThePanAngle) {
  const cv::Size size(320, 240);
  const Eigen::Matrix3d K = intrinsics(500, size);
  EXPECT_DOUBLE_EQ(overlapFraction(cv::Matx33d::eye(), size), 1.0);
  // A pure horizontal shift of a quarter of the width leaves three quarters overlapping.
  const cv::Matx33d shift(1, 0, 80, 0, 1, 0, 0, 0, 1);
  EXPECT_NEAR(overlapFraction(shift, size), 0.75, 1.0 / 64);
  double previous = 1.0;
  for (double deg : {5.0, 15.0, 25.0}) {
    const double o = overlapFraction(
        rotationHomography(K,
                           Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitY()).matrix()),
        size);
    EXPECT_LT(o, previous) << deg;
    previous = o;
  }
  // Half field of view is atan(160 / 500) = 17.7 deg: a 40 deg pan sees nothing of it.
  EXPECT_EQ(
      overlapFraction(rotationHomography(
                          K, Eigen::AngleAxisd(40 * M_PI / 180, Eigen::Vector3d::UnitY()).matrix()),
                      size),
      0.0);
}

TEST(HomographyGroundTruth, ErrorsMeasureTheDisplacement) {
  const cv::Size size(320, 240);
  const cv::Matx33d truth = cv::Matx33d::eye();
  const cv::Matx33d off(1, 0, 0.3, 0, 1, -0.4, 0, 0, 1);  // 0.5 px everywhere
  const auto grid = annotationGrid(size, 9, 7);
  ASSERT_EQ(grid.size(), 63u);
  EXPECT_NEAR(meanTransferDeviation(off, truth, grid, size), 0.5, 1e-12);
  EXPECT_NEAR(frameCornerError(off, truth, size), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(frameCornerError(truth, truth, size), 0.0);
  // No annotation inside the frame: nothing to score.
  const cv::Matx33d away(1, 0, 1000, 0, 1, 0, 0, 0, 1);
  EXPECT_TRUE(std::isnan(meanTransferDeviation(away, away, grid, size)));
}
