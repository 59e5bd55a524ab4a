#include "app/simulator/BrickWallScene.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "ErrorMessage.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/homography/HomographyDlt.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

double meanGrey(const cv::Mat& bgr32) {
  cv::Mat grey;
  cv::cvtColor(bgr32, grey, cv::COLOR_BGR2GRAY);
  return cv::mean(grey)[0];
}

}  // namespace

// Head-on, the joints (light mortar) fall where the pattern puts them: the joint between two
// courses is brighter than the middle of the bricks on either side, and the running bond shifts
// every other course by half a brick.
TEST(BrickWallScene, DrawsTheBondWhereItsGeometryPutsIt) {
  const BrickWallStyle style;
  const BrickWallTexture wall(1, style);
  const double pitchY = style.unitHeightM + style.jointM;
  double joint = 0, brick = 0;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.013 * i;
    joint += cv::norm(wall.at(x, pitchY * 3));                 // on a bed joint
    brick += cv::norm(wall.at(x, pitchY * 3 + 0.5 * pitchY));  // mid-course
  }
  EXPECT_GT(joint, 1.3 * brick);
  // Running bond: a head joint of course 0 at x = 0 lies mid-brick in course 1.
  const double y0 = 0.5 * pitchY, y1 = 1.5 * pitchY;
  EXPECT_GT(cv::norm(wall.at(0.0, y0)), cv::norm(wall.at(0.0, y1)) * 1.2);
  // The same seed gives the same wall; another seed other bricks.
  EXPECT_EQ(wall.at(0.31, 0.47), BrickWallTexture(1, style).at(0.31, 0.47));
  EXPECT_NE(wall.at(0.31, 0.47), BrickWallTexture(2, style).at(0.31, 0.47));
}

// Two views of a wall without relief (jointDepthM = 0), from different cameras and sizes: the
// frame sampled back through the exact homography of planeToImage reproduces the reference (both
// rendered with 4x4 sub-samples: their area sampling differs by a fraction of a grey level).
TEST(BrickWallScene, ViewsOfAFlatWallAreRelatedByTheirHomography) {
  BrickWallStyle flat;
  flat.jointDepthM = 0.0;
  const BrickWallTexture wall(3, flat);
  const PinholeCamera a = PinholeCamera::fromFieldOfView({320, 240}, 55.0);
  const PinholeCamera b = PinholeCamera::fromFieldOfView({280, 220}, 50.0);
  const Eigen::Matrix4d poseA = wallViewPose({0, 0}, 1.0, 0, 0, 0);
  const Eigen::Matrix4d poseB = wallViewPose({0.05, 0.02}, 0.9, 30, 90, 10);
  const cv::Mat viewA = renderWallView(wall, a.K(), poseA, a.imageSize());
  const cv::Mat viewB = renderWallView(wall, b.K(), poseB, b.imageSize());
  ASSERT_EQ(viewB.size(), b.imageSize());
  const cv::Matx33d H = planeToImage(b.K(), poseB) * planeToImage(a.K(), poseA).inv();
  cv::Mat back, seen;
  cv::warpPerspective(viewB, back, H, a.imageSize(), cv::INTER_LINEAR | cv::WARP_INVERSE_MAP);
  cv::warpPerspective(cv::Mat(b.imageSize(), CV_8UC1, cv::Scalar(255)), seen, H, a.imageSize(),
                      cv::INTER_NEAREST | cv::WARP_INVERSE_MAP);
  cv::erode(seen, seen, cv::Mat(), cv::Point(-1, -1), 3);
  ASSERT_GT(cv::countNonZero(seen), 20000);
  cv::Mat diff;
  cv::absdiff(back, viewA, diff);
  // Bilinear resampling of sharp joints costs a few grey levels on average; a pixel-centre or
  // homography error of half a pixel would cost several times more on these edges.
  EXPECT_LT(cv::mean(diff, seen)[0], 6.0);
  EXPECT_GT(meanGrey(viewA), 50.0);
}

// Recessed joints: head-on the views with and without relief differ only a little (the joint
// floor is shaded), seen from 60 degrees they differ along the joints (their sides and floor
// shift against the faces), and the faces themselves do not move.
TEST(BrickWallScene, RecessedJointsShiftWithTheViewpoint) {
  BrickWallStyle flat, deep;
  flat.jointDepthM = 0.0;
  deep.jointDepthM = 0.012;
  const BrickWallTexture a(4, flat), b(4, deep);
  const PinholeCamera camera = PinholeCamera::fromFieldOfView({240, 180}, 50.0);
  const auto difference = [&](const Eigen::Matrix4d& pose) {
    cv::Mat diff;
    cv::absdiff(renderWallView(a, camera.K(), pose, camera.imageSize(), 2),
                renderWallView(b, camera.K(), pose, camera.imageSize(), 2), diff);
    return cv::mean(diff);
  };
  const double headOn = cv::norm(difference(wallViewPose({0, 0}, 0.8, 0, 0, 0)));
  const double oblique = cv::norm(difference(wallViewPose({0, 0}, 0.8, 60, 90, 0)));
  EXPECT_GT(oblique, 1.5 * headOn);
  // A point on a unit's face sees the same colour either way.
  const BrickWallStyle& s = deep;
  const double mid = 0.5 * s.jointM + 0.5 * s.unitWidthM;
  EXPECT_EQ(a.at(mid, 0.5 * s.jointM + 0.5 * s.unitHeightM),
            b.seen(mid, 0.5 * s.jointM + 0.5 * s.unitHeightM, mid + 0.01,
                   0.5 * s.jointM + 0.5 * s.unitHeightM));
}

TEST(BrickWallScene, BadStyleAndViewsAreRefusedByName) {
  BrickWallStyle s;
  s.jointM = 0.2;
  EXPECT_NE(test::errorMessage([&] { s.check(); }).find("jointM"), std::string::npos);
  s = {};
  s.chipContrast = 1.5;
  EXPECT_NE(test::errorMessage([&] { BrickWallTexture(1, s); }).find("chipContrast"),
            std::string::npos);
  EXPECT_THROW(wallViewPose({0, 0}, 0.0, 0, 0, 0), Error);
  const BrickWallTexture wall(1);
  const PinholeCamera camera = PinholeCamera::fromFieldOfView({64, 48}, 50.0);
  EXPECT_THROW(renderWallView(wall, camera.K(), wallViewPose({0, 0}, 1, 0, 0, 0), {0, 0}), Error);
  EXPECT_THROW(renderWallView(wall, camera.K(), wallViewPose({0, 0}, 1, 0, 0, 0), {64, 48}, 0),
               Error);
}
