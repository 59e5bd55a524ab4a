// TwoViewMotion on exact views of a textured plane (PlanarTestScene, 600 px focal length, ~1 m)
// and on real frames: a sideways move is measured (its rotation and direction), a pure rotation,
// too small a move, a textureless view and two views of different places are refused with what
// to do; a real frame turned on the spot (the ViSP clip's frame 0 through K R K^-1) and two real
// desk frames 1.6 mm apart are refused as rotations.
#include "engine/reference/TwoViewMotion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ErrorMessage.hpp"
#include "PlanarTestScene.hpp"
#include "TestPaths.hpp"

namespace reftrack {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

using test::PlanarTestScene;

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * kRadToDeg;
}

// The truth's motion from A to B (unit translation).
RigidPose motion(const RigidPose& A, const RigidPose& B) {
  const RigidPose m = B * A.inverse();
  return RigidPose(m.rotation(), m.translation().normalized());
}

class TwoViewMotionTest : public ::testing::Test {
 protected:
  PlanarTestScene scene;
  const RigidPose A = PlanarTestScene::lookAt({0.0, -0.1, 1.0}, {0.0, 0.0, 0.0});
  TwoViewMotionEstimator estimator{scene.camera};
};

TEST_F(TwoViewMotionTest, ASidewaysMoveIsMeasured) {
  const RigidPose B = PlanarTestScene::lookAt({0.12, -0.08, 1.0}, {0.03, 0.0, 0.0});
  const TwoViewMotion m = estimator.estimate(scene.render(A), scene.render(B));
  ASSERT_TRUE(m.usable()) << m.refusal;
  std::printf("%s\n", m.summary().c_str());
  EXPECT_GT(m.matches, 300);
  EXPECT_GT(m.inliers, 0.8 * m.matches);
  EXPECT_LT(m.rotationShare, 0.1);
  // 12 cm at 1 m: about 7 degrees between the rays (the look-at point moves with the camera).
  EXPECT_GT(m.medianParallaxDeg, 4.0);
  EXPECT_LT(m.medianParallaxDeg, 9.0);
  EXPECT_GT(m.medianParallaxPx, 40.0);
  // A plane: the essential matrix and the homography both see the motion; the best of them is
  // within a small fraction of a degree (exact views, 1 grey level of noise; sub-pixel keypoints).
  const RigidPose truth = motion(A, B);
  double bestTurn = RigidPose::rotationDistance(m.firstToSecond, truth) * kRadToDeg;
  double bestDirection = angleDeg(m.firstToSecond.translation(), truth.translation());
  for (const RigidPose& p : m.planeMotions) {
    const double turn = RigidPose::rotationDistance(p, truth) * kRadToDeg;
    if (turn < bestTurn) {
      bestTurn = turn;
      bestDirection = angleDeg(p.translation(), truth.translation());
    }
  }
  EXPECT_LT(bestTurn, 0.2);
  EXPECT_LT(bestDirection, 2.0);
  // The direction in words: the camera moved right (+x of the first camera).
  EXPECT_GT(m.direction.x(), 0.8);
  EXPECT_NE(m.summary().find("moved right"), std::string::npos) << m.summary();
}

TEST_F(TwoViewMotionTest, APureRotationIsRefused) {
  // The same centre, looking 5 degrees to the side.
  const RigidPose turned = PlanarTestScene::lookAt({0.0, -0.1, 1.0}, {0.09, 0.0, 0.0});
  const TwoViewMotion m = estimator.estimate(scene.render(A), scene.render(turned));
  EXPECT_FALSE(m.usable());
  EXPECT_GT(m.rotationShare, 0.9);
  EXPECT_NE(m.refusal.find("the camera turned but hardly moved"), std::string::npos) << m.refusal;
  EXPECT_NE(m.refusal.find("move the camera sideways"), std::string::npos) << m.refusal;
}

TEST_F(TwoViewMotionTest, TooSmallAMoveIsRefused) {
  // 1.5 cm at 1 m: under a degree between the rays (min_parallax_deg 1.5).
  const RigidPose B = PlanarTestScene::lookAt({0.015, -0.1, 1.0}, {0.015, 0.0, 0.0});
  const TwoViewMotion m = estimator.estimate(scene.render(A), scene.render(B));
  EXPECT_FALSE(m.usable());
  const bool parallax = m.refusal.find("too little parallax") != std::string::npos;
  const bool rotation = m.refusal.find("turned but hardly moved") != std::string::npos;
  EXPECT_TRUE(parallax || rotation) << m.refusal;
  std::printf("1.5 cm sideways: %s\n", m.refusal.c_str());
  EXPECT_LT(m.medianParallaxDeg, 1.5);
}

TEST_F(TwoViewMotionTest, ATexturelessViewIsRefused) {
  const cv::Mat blank(scene.camera.imageSize(), CV_8UC1, cv::Scalar(128));
  const TwoViewMotion m = estimator.estimate(scene.render(A), blank);
  EXPECT_FALSE(m.usable());
  EXPECT_EQ(m.keypointsSecond, 0);
  EXPECT_NE(m.refusal.find("the second view is textureless: 0 sift keypoints"), std::string::npos)
      << m.refusal;
  EXPECT_NE(m.refusal.find("point the camera at a textured part"), std::string::npos);
  EXPECT_NE(estimator.texturelessRefusal(estimator.describe(blank), "captured"), "");
  EXPECT_EQ(estimator.texturelessRefusal(estimator.describe(scene.render(A)), "captured"), "");
}

TEST_F(TwoViewMotionTest, TwoDifferentPlacesAreRefused) {
  // The other corner of the texture, close up: nothing in common with A's view.
  const RigidPose far = PlanarTestScene::lookAt({0.65, 0.48, 0.25}, {0.65, 0.48, 0.0});
  const TwoViewMotion m = estimator.estimate(scene.render(A), scene.render(far));
  EXPECT_FALSE(m.usable());
  EXPECT_TRUE(m.refusal.find("share too little") != std::string::npos ||
              m.refusal.find("fit no camera motion") != std::string::npos)
      << m.refusal;
}

TEST_F(TwoViewMotionTest, AnImageOfAnotherSizeThrows) {
  const cv::Mat small(240, 320, CV_8UC1, cv::Scalar(0));
  EXPECT_NE(test::errorMessage([&] {
              estimator.describe(small);
            }).find("the image is 320x240 but the camera is for 640x480 images"),
            std::string::npos);
}

TEST(TwoViewMotionRealFrames, ARealFrameTurnedOnTheSpotIsRefused) {
  const std::optional<std::filesystem::path> data = test::sharedDataDir();
  const std::filesystem::path clip = data ? *data / "visp-desk-apriltags" : std::filesystem::path();
  if (!data || !std::filesystem::exists(clip / "frames" / "000000.png"))
    GTEST_SKIP() << "../shared/data/visp-desk-apriltags not available";
  const PinholeCamera camera = PinholeCamera::load(clip / "camera.yml");  // no lens distortion
  const cv::Mat first = cv::imread((clip / "frames" / "000000.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(first.empty());
  // The camera turned 4 degrees about its vertical axis and 1 about its optical axis: the
  // image through H = K R K^-1 (the parts turned out of view are black).
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(4.0 / kRadToDeg, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(1.0 / kRadToDeg, Eigen::Vector3d::UnitZ()))
                                .toRotationMatrix();
  const Eigen::Matrix3d H = camera.K() * R * camera.K().inverse();
  cv::Mat Hcv, turned;
  cv::eigen2cv(H, Hcv);
  cv::warpPerspective(first, turned, Hcv, first.size(), cv::INTER_LINEAR);
  const TwoViewMotion m = TwoViewMotionEstimator(camera).estimate(first, turned);
  std::printf("ViSP frame 0 turned on the spot: %s\n", m.summary().c_str());
  EXPECT_FALSE(m.usable());
  EXPECT_NE(m.refusal.find("the camera turned but hardly moved"), std::string::npos) << m.refusal;
  // ... while the clip's frame 40 (11 cm away) from the same frame 0 is a usable pair.
  const cv::Mat moved = cv::imread((clip / "frames" / "000040.png").string(), cv::IMREAD_COLOR);
  const TwoViewMotion real = TwoViewMotionEstimator(camera).estimate(first, moved);
  EXPECT_TRUE(real.usable()) << real.refusal;
  EXPECT_LT(real.rotationShare, 0.3);
}

}  // namespace
}  // namespace reftrack

namespace reftrack {
namespace {

// The real desk clip's frames 0 and 2 (the camera moved 1.6 mm and turned 0.5 degrees between
// them, 0.3 m from the desk): refused, a rotation explaining most matches or too little
// parallax; frames 0 and 40 (3.95 cm) are a usable pair.
TEST(TwoViewMotionRealFrames, RealFramesBarelyApartAreRefused) {
  const std::optional<std::filesystem::path> data = test::sharedDataDir();
  const std::filesystem::path clip = data ? *data / "desk-chessboard" : std::filesystem::path();
  if (!data || !std::filesystem::exists(clip / "frames" / "000040.jpg"))
    GTEST_SKIP() << "../shared/data/desk-chessboard not available";
  const PinholeCamera camera = PinholeCamera::load(clip / "camera.yml");
  const auto frame = [&](const char* name) {
    return cv::imread((clip / "frames" / name).string(), cv::IMREAD_COLOR);
  };
  const TwoViewMotionEstimator estimator(camera);
  const TwoViewMotion near = estimator.estimate(frame("000000.jpg"), frame("000002.jpg"));
  std::printf("desk frames 0 and 2: %s\n", near.refusal.c_str());
  EXPECT_FALSE(near.usable());
  EXPECT_TRUE(near.refusal.find("turned but hardly moved") != std::string::npos ||
              near.refusal.find("too little parallax") != std::string::npos)
      << near.refusal;
  const TwoViewMotion apart = estimator.estimate(frame("000000.jpg"), frame("000040.jpg"));
  EXPECT_TRUE(apart.usable()) << apart.refusal;
  EXPECT_GT(apart.medianParallaxDeg, 3.0);  // measured 5.1 deg
}

}  // namespace
}  // namespace reftrack
