// UnpreparedInitializer on exact views of a textured plane (PlanarTestScene) and on the real desk
// clip: the relative pose of the first two references from their own matches, the world on the
// dominant plane (z toward the cameras, x along the first camera's x), the scale from the
// baseline or from two marked points, a third reference added as `extend` adds one, and the
// refusals (a pure rotation, a bad length, a single image).
#include "engine/mapping/UnpreparedInitializer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "engine/reference/PlanarTestScene.hpp"

namespace reftrack {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;

using test::PlanarTestScene;

double angleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * kRadToDeg;
}

MapExtenderParams quickParams() {
  MapExtenderParams p;
  return p;
}

class UnpreparedInitializerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { scene_ = new PlanarTestScene(); }
  static void TearDownTestSuite() { delete scene_; }
  static PlanarTestScene* scene_;
  const RigidPose A = PlanarTestScene::lookAt({0.0, -0.1, 1.0}, {0.0, 0.0, 0.0});
  const RigidPose B = PlanarTestScene::lookAt({0.12, -0.08, 1.0}, {0.03, 0.0, 0.0});
  const RigidPose C = PlanarTestScene::lookAt({-0.1, -0.16, 0.95}, {0.0, 0.02, 0.0});
  const double baseline = (A.cameraCentre() - B.cameraCentre()).norm();
  std::vector<ReferenceImage> images(std::initializer_list<RigidPose> poses) const {
    std::vector<ReferenceImage> out;
    for (const RigidPose& T : poses)
      out.push_back({scene_->render(T), "view_" + std::to_string(out.size())});
    return out;
  }
};
PlanarTestScene* UnpreparedInitializerTest::scene_ = nullptr;

TEST_F(UnpreparedInitializerTest, TwoViewsAndTheBaselineGiveTheTruePosesOnThePlane) {
  const UnpreparedInitializer init(scene_->camera, quickParams());
  const UnpreparedMap built = init.build(images({A, B}), MetricScale::baseline(baseline));
  const MultiReferenceMap& map = built.prepared.map;
  ASSERT_EQ(map.size(), 2);
  EXPECT_GT(map.points.size(), 150u);
  std::printf("%s; start: %s\n", built.report.motion.summary().c_str(), built.report.start.c_str());
  // The relative pose: exact views, so within hundredths of a degree; the length is the one given.
  const RigidPose relative = map.views[1].T * map.views[0].T.inverse();
  const RigidPose truth = B * A.inverse();
  const double turn = RigidPose::rotationDistance(relative, truth) * kRadToDeg;
  const double direction = angleDeg(relative.cameraCentre(), truth.cameraCentre());
  std::printf("relative pose off the truth by %.4f deg, direction %.3f deg\n", turn, direction);
  EXPECT_LT(turn, 0.05);
  EXPECT_LT(direction, 0.5);
  EXPECT_NEAR(relative.translation().norm(), baseline, 1e-9);
  EXPECT_NEAR(built.report.baselineMetres, baseline, 1e-9);
  // The world: the plane (the truth's z = 0, z toward the cameras), so the map's world differs
  // from the truth's by a turn about z and a shift on the plane only.
  ASSERT_TRUE(built.report.onPlane);
  const RigidPose oursToTruth = A.inverse() * map.views[0].T;
  EXPECT_LT(angleDeg(oursToTruth.rotation() * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()),
            0.3);
  EXPECT_LT(std::abs((oursToTruth * Eigen::Vector3d::Zero()).z()), 0.002);
  std::vector<double> heights;
  for (const MapPoint& p : map.points) heights.push_back(std::abs(p.world.z()));
  std::sort(heights.begin(), heights.end());
  const double medianHeight = heights[heights.size() / 2], p90 = heights[heights.size() * 9 / 10];
  std::printf("points off the plane: median %.2f mm, 90th percentile %.2f mm\n",
              1000.0 * medianHeight, 1000.0 * p90);
  EXPECT_LT(medianHeight, 0.001);
  EXPECT_LT(p90, 0.005);
  for (const ReferenceView& v : map.views) EXPECT_GT(v.T.cameraCentre().z(), 0.5);
  // x: the first camera's x laid onto the plane.
  const Eigen::Matrix3d& R0 = map.views[0].T.rotation();  // world -> camera 0
  const Eigen::Vector3d normal = R0.col(2), cameraX = Eigen::Vector3d::UnitX();
  EXPECT_LT(angleDeg(R0.col(0), cameraX - normal * normal.dot(cameraX)), 0.01);
  // The map carries its keypoint layer like any prepared map, and says where its poses came from.
  EXPECT_GT(map.views[0].keypoints.pointCount(), 50);
  EXPECT_NE(map.poseSource.find("unprepared"), std::string::npos) << map.poseSource;
}

TEST_F(UnpreparedInitializerTest, TwoMarkedPointsOnThePlaneGiveTheScale) {
  // Two texture points 0.25 m apart, marked where the first view sees them.
  const Eigen::Vector3d P(-0.1, -0.05, 0.0), Q(0.14, 0.02, 0.0);
  const Eigen::Vector2d p = scene_->camera.project(A, P), q = scene_->camera.project(A, Q);
  const UnpreparedInitializer init(scene_->camera, quickParams());
  const UnpreparedMap built = init.build(
      images({A, B}), MetricScale::distance((P - Q).norm(), {p.x(), p.y()}, {q.x(), q.y()}));
  // Pixel-exact marks on exact views: the baseline within 0.5%.
  EXPECT_NEAR(built.report.baselineMetres / baseline, 1.0, 0.005);
  EXPECT_NEAR((built.report.distanceFirst - built.report.distanceSecond).norm(), (P - Q).norm(),
              1e-9);
  EXPECT_NEAR(built.report.distanceFirst.z(), 0.0, 1e-9);
  // Two marks on one spot are refused before anything is built.
  EXPECT_NE(
      test::errorMessage([&] {
        init.build(images({A, B}), MetricScale::distance(0.2, {p.x(), p.y()}, {p.x() + 3, p.y()}));
      }).find("px apart (at least 10 needed)"),
      std::string::npos);
}

TEST_F(UnpreparedInitializerTest, AThirdReferenceIsAddedAsExtendAddsOne) {
  const UnpreparedInitializer init(scene_->camera, quickParams());
  const UnpreparedMap built = init.build(images({A, B, C}), MetricScale::baseline(baseline));
  const MultiReferenceMap& map = built.prepared.map;
  ASSERT_EQ(map.size(), 3);
  ASSERT_EQ(built.report.added.size(), 1u);
  EXPECT_FALSE(map.views[2].anchored);
  EXPECT_TRUE(built.report.closingAdjustment.has_value());
  // C relative to A, against the truth: millimetres and hundredths of a degree.
  const RigidPose relative = map.views[2].T * map.views[0].T.inverse(), truth = C * A.inverse();
  const double mm = 1000.0 * (relative.cameraCentre() - truth.cameraCentre()).norm();
  const double deg = RigidPose::rotationDistance(relative, truth) * kRadToDeg;
  std::printf("third reference: %.2f mm, %.4f deg off the truth\n", mm, deg);
  EXPECT_LT(mm, 1.0);
  EXPECT_LT(deg, 0.05);
  EXPECT_GT(map.views[2].keypoints.pointCount(), 50);
}

TEST_F(UnpreparedInitializerTest, PairsThatCannotStartAMapAndBadInputAreRefused) {
  const UnpreparedInitializer init(scene_->camera, quickParams());
  const RigidPose turned = PlanarTestScene::lookAt({0.0, -0.1, 1.0}, {0.09, 0.0, 0.0});
  EXPECT_NE(test::errorMessage([&] {
              init.build(images({A, turned}), MetricScale::baseline(0.05));
            })
                .find("references 'view_0' and 'view_1' cannot start a map: the camera turned but "
                      "hardly moved"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] {
              init.build(images({A, B}), MetricScale::baseline(-0.1));
            }).find("the baseline must be a finite length"),
            std::string::npos);
  EXPECT_NE(
      test::errorMessage([&] {
        init.build(images({A, B}), MetricScale::baseline(std::numeric_limits<double>::quiet_NaN()));
      }).find("the baseline must be a finite length"),
      std::string::npos);
  EXPECT_NE(test::errorMessage([&] {
              init.build(images({A}), MetricScale::baseline(0.1));
            }).find("at least 2 reference images"),
            std::string::npos);
  UnpreparedMapParams bad;
  bad.minParallaxDeg = -1;
  EXPECT_NE(test::errorMessage([&] {
              UnpreparedInitializer(scene_->camera, quickParams(), bad);
            }).find("unprepared.min_parallax_deg"),
            std::string::npos);
}

// The real desk clip (../shared/data/desk-chessboard), references 0 and 40 (3.95 cm apart, 12
// degrees turned), mapped without their true poses.
TEST(UnpreparedInitializerRealFootage, DeskFramesZeroAndFortyMappedWithoutTheirPoses) {
  const std::optional<std::filesystem::path> data = test::sharedDataDir();
  const std::filesystem::path clip = data ? *data / "desk-chessboard" : std::filesystem::path();
  if (!data || !std::filesystem::exists(clip / "groundtruth.txt"))
    GTEST_SKIP() << "../shared/data/desk-chessboard not available";
  const PinholeCamera camera = PinholeCamera::load(clip / "camera.yml");
  const TumTrajectory truth = TumTrajectory::load(clip / "groundtruth.txt");
  const RigidPose T0 = truth.poses[0].worldToCamera, T40 = truth.poses[40].worldToCamera;
  const std::vector<ReferenceImage> images = {
      {cv::imread((clip / "frames" / "000000.jpg").string(), cv::IMREAD_COLOR), "frame 0"},
      {cv::imread((clip / "frames" / "000040.jpg").string(), cv::IMREAD_COLOR), "frame 40"}};
  const double baseline = (T0.cameraCentre() - T40.cameraCentre()).norm();
  const UnpreparedInitializer init(camera, MapExtenderParams{});
  const UnpreparedMap built = init.build(images, MetricScale::baseline(baseline));
  const MultiReferenceMap& map = built.prepared.map;
  const RigidPose relative = map.views[1].T * map.views[0].T.inverse(),
                  expected = T40 * T0.inverse();
  const double turn = RigidPose::rotationDistance(relative, expected) * kRadToDeg;
  const double direction = angleDeg(relative.cameraCentre(), expected.cameraCentre());
  std::printf(
      "desk 0/40: %zu points, relative pose %.3f deg and direction %.2f deg off the true "
      "poses'\n",
      map.points.size(), turn, direction);
  EXPECT_GT(map.points.size(), 100u);
  // Measured 0.39 deg and 3.4 deg: the clip's own corners, matched and refined from any start
  // (the essential matrix, the plane's homography, the true relative pose itself), settle there,
  // and random halves of them within 0.05 deg of it; the board-fitted true poses and this
  // calibration disagree with the images by that much (see the research guide). The bounds
  // leave room for that, not for a wrong motion (a few degrees).
  EXPECT_LT(turn, 0.6);
  EXPECT_LT(direction, 5.0);
  // The dominant plane is the desk: the map's z is the board's normal (the truth's z).
  const RigidPose oursToTruth = T0.inverse() * map.views[0].T;
  EXPECT_LT(angleDeg(oursToTruth.rotation() * Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ()),
            2.0);

  // The scale from the board's first row of inner corners, 0.32 m long, marked in frame 0.
  const Eigen::Vector2d p = camera.projectDistorted(T0 * Eigen::Vector3d(0.0, 0.0, 0.0));
  const Eigen::Vector2d q = camera.projectDistorted(T0 * Eigen::Vector3d(0.32, 0.0, 0.0));
  const UnpreparedMap marked =
      init.build(images, MetricScale::distance(0.32, {p.x(), p.y()}, {q.x(), q.y()}));
  std::printf("desk 0/40 scaled by 0.32 m on the board: baseline %.2f mm (true %.2f mm)\n",
              1000.0 * marked.report.baselineMetres, 1000.0 * baseline);
  // Measured 1.3% short: the plane fitted to the desk's points and the relative pose above.
  EXPECT_NEAR(marked.report.baselineMetres / baseline, 1.0, 0.03);
}

}  // namespace
}  // namespace reftrack
