#include "app/simulator/SceneSimulator.hpp"

#include <gtest/gtest.h>

#include <opencv2/aruco.hpp>
#include <opencv2/imgproc.hpp>

#include "engine/core/Error.hpp"
#include "engine/reference/MarkerPoseEstimator.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

// One GL context and one 640x480 handheld simulator for the whole suite (building the scene and
// uploading its textures is the slow part).
class SceneSimulatorTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    context_ = render::createHeadlessContext().release();
    SimulationOptions o;
    o.frames = 30;
    sim_ = new SceneSimulator(o);
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete context_;
  }
  static render::GlContext* context_;
  static SceneSimulator* sim_;
};
render::GlContext* SceneSimulatorTest::context_ = nullptr;
SceneSimulator* SceneSimulatorTest::sim_ = nullptr;

std::vector<cv::Point2f> detectMarkerCorners(const cv::Mat& image, const MarkerSpec& marker) {
  auto params = cv::aruco::DetectorParameters::create();
  params->cornerRefinementMethod = cv::aruco::CORNER_REFINE_SUBPIX;
  std::vector<std::vector<cv::Point2f>> corners;
  std::vector<int> ids;
  cv::aruco::detectMarkers(image, cv::aruco::getPredefinedDictionary(marker.dictionaryEnum()),
                           corners, ids, params);
  if (ids.size() != 1 || ids[0] != marker.id) return {};
  return corners[0];
}

}  // namespace

TEST_F(SceneSimulatorTest, ArucoCornersLandWhereTheCameraModelProjectsThem) {
  for (char which : {'A', 'B'}) {
    const cv::Mat image = sim_->renderReference(which);
    ASSERT_EQ(image.type(), CV_8UC3);
    ASSERT_EQ(image.size(), cv::Size(640, 480));
    const auto detected = detectMarkerCorners(image, sim_->marker());
    ASSERT_EQ(detected.size(), 4u) << which;
    const RigidPose pose = which == 'A' ? sim_->referencePoseA() : sim_->referencePoseB();
    const auto truth = sim_->marker().cornersWorld();
    double worst = 0.0;
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector2d p = sim_->camera().project(pose, truth[c]);
      worst = std::max(worst, std::hypot(detected[c].x - p.x(), detected[c].y - p.y()));
    }
    // The renderer's pixel-centre convention plus 3x anti-aliasing: ArUco's sub-pixel corners
    // must agree with K[R|t]X as they would on a real, well-calibrated camera.
    EXPECT_LT(worst, 0.3) << which;
    std::cout << "reference " << which << ": worst ArUco corner error " << worst << " px\n";
  }
}

TEST_F(SceneSimulatorTest, MarkerPoseEstimatorRecoversTheReferencePoses) {
  const MarkerPoseEstimator estimator(sim_->marker(), sim_->camera());
  for (char which : {'A', 'B'}) {
    const RigidPose truth = which == 'A' ? sim_->referencePoseA() : sim_->referencePoseB();
    const MarkerPose got = estimator.estimate(sim_->renderReference(which), "reference");
    const double dt = RigidPose::translationDistance(got.worldToCamera, truth);
    const double dr = RigidPose::rotationDistance(got.worldToCamera, truth) * 180.0 / M_PI;
    // Issue 5's accuracy for reference poses from the marker: 2 mm and 0.1 degree.
    EXPECT_LT(dt, 0.002) << which;
    EXPECT_LT(dr, 0.1) << which;
    std::cout << "reference " << which << ": marker pose error " << dt * 1000 << " mm, " << dr
              << " deg\n";
  }
}

// Through a k1 = -0.3 lens (50 degrees) the marker still gives the reference poses to issue 5's
// 2 mm and 0.1 degree: its sides are fitted on the undistorted image (refining on the recorded
// one, where the lens bends them, put reference A's centre 3.6 mm off).
TEST(SceneSimulatorLens, MarkerPoseEstimatorRecoversTheReferencePosesThroughTheLens) {
  const auto context = render::createHeadlessContext();
  SimulationOptions o;
  o.frames = 2;
  o.fovDeg = 50.0;
  o.distortion = {-0.3, 0.0, 0.0, 0.0};
  SceneSimulator sim(o);
  const MarkerPoseEstimator estimator(sim.marker(), sim.camera());
  for (char which : {'A', 'B'}) {
    const RigidPose truth = which == 'A' ? sim.referencePoseA() : sim.referencePoseB();
    const MarkerPose got = estimator.estimate(sim.renderReference(which), "reference");
    const double dt = RigidPose::translationDistance(got.worldToCamera, truth);
    const double dr = RigidPose::rotationDistance(got.worldToCamera, truth) * 180.0 / M_PI;
    EXPECT_LT(dt, 0.002) << which;
    EXPECT_LT(dr, 0.1) << which;
    std::cout << "through the lens, reference " << which << ": marker pose error " << dt * 1000
              << " mm, " << dr << " deg\n";
  }
}

TEST(SceneSimulatorReferences, ReferenceBaselinePlacesBThatFarFromA) {
  // --reference-baseline: B moves along the A->B direction of the scene (sideways), A stays.
  const auto context = render::createHeadlessContext();
  SimulationOptions o;
  o.frames = 2;
  const SceneSimulator wide(o);
  o.referenceBaseline = 0.04;
  const SceneSimulator narrow(o);
  const Eigen::Vector3d a = narrow.referencePoses()[0].cameraCentre();
  EXPECT_LT((a - wide.referencePoses()[0].cameraCentre()).norm(), 1e-12);
  EXPECT_NEAR((narrow.referencePoses()[1].cameraCentre() - a).norm(), 0.04, 1e-12);
  EXPECT_NEAR((wide.referencePoses()[1].cameraCentre() - a).norm(), 0.25, 1e-12);
  const Eigen::Vector3d dirWide = (wide.referencePoses()[1].cameraCentre() - a).normalized();
  const Eigen::Vector3d dirNarrow = (narrow.referencePoses()[1].cameraCentre() - a).normalized();
  EXPECT_GT(dirWide.dot(dirNarrow), 1.0 - 1e-12);
}

TEST(SceneSimulatorReferences, TheMarkerPosesEveryWalkaroundReference) {
  // The extra views are posed from the marker by `reftrack prepare` like A and B: it must be
  // visible and accurate in each of them.
  const auto context = render::createHeadlessContext();
  SimulationOptions o;
  o.preset = "walkaround";
  o.frames = 2;
  o.references = 8;
  SceneSimulator sim(o);
  ASSERT_EQ(sim.referencePoses().size(), 8u);
  const MarkerPoseEstimator estimator(sim.marker(), sim.camera());
  for (int i = 0; i < 8; ++i) {
    const RigidPose truth = sim.referencePoses()[i];
    const MarkerPose got = estimator.estimate(sim.renderReferenceView(i), "reference");
    const double dt = RigidPose::translationDistance(got.worldToCamera, truth);
    const double dr = RigidPose::rotationDistance(got.worldToCamera, truth) * 180.0 / M_PI;
    // The views 2.. see the marker more obliquely and from up to 1.2 m than A and B: 3 mm and
    // 0.2 degree (A and B: 2 mm, 0.1 degree above).
    EXPECT_LT(dt, 0.003) << i;
    EXPECT_LT(dr, 0.2) << i;
    std::cout << "reference " << i << ": marker pose error " << dt * 1000 << " mm, " << dr
              << " deg\n";
  }
  EXPECT_THROW(sim.renderReferenceView(8), Error);
  EXPECT_THROW(sim.renderReferenceView(-1), Error);
}

TEST_F(SceneSimulatorTest, DepthIsTheTrueSurfaceDistance) {
  const RigidPose pose = sim_->referencePoseA();
  const cv::Mat depth = sim_->renderDepth(pose);
  ASSERT_EQ(depth.type(), CV_32F);
  const Eigen::Vector2d centre = sim_->camera().project(pose, Eigen::Vector3d::Zero());
  const int u = static_cast<int>(std::lround(centre.x())),
            v = static_cast<int>(std::lround(centre.y()));
  // True depth at that pixel's centre: its ray meets the desk plane z = 0.
  const Eigen::Vector3d ray = sim_->camera().K().inverse() * Eigen::Vector3d(u, v, 1);
  const Eigen::Vector3d rayWorld = pose.rotation().transpose() * ray;
  const Eigen::Vector3d origin = pose.cameraCentre();
  const double s = -origin.z() / rayWorld.z();  // camera z of the hit, since ray.z() = 1
  // A 24-bit depth buffer over 0.02..20 m resolves ~5 um at 1 m; 1 mm is the brief's bound.
  EXPECT_NEAR(depth.at<float>(v, u), s, 0.001);
  // The scene spans the brief's depth range as seen from the reference camera.
  double nearest = 0.0, farthest = 0.0;
  cv::minMaxLoc(depth, &nearest, &farthest, nullptr, nullptr, depth > 0);
  EXPECT_GT(nearest, 0.4);
  EXPECT_LT(farthest, 2.5);
  EXPECT_GT(farthest - nearest, 0.8);
  EXPECT_EQ(cv::countNonZero(depth > 0), depth.rows * depth.cols) << "background visible from A";
  std::cout << "depth from A: " << nearest << " .. " << farthest << " m\n";
}

TEST_F(SceneSimulatorTest, FramesAreDeterministicInTheSeed) {
  const cv::Mat a = sim_->renderFrame(5), b = sim_->renderFrame(5);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
  EXPECT_LT(RigidPose::translationDistance(sim_->framePose(0), sim_->referencePoseA()), 1e-12);
  // Frame 0 of the handheld path is view A: same clean image, different noise stream.
  const cv::Mat frame0 = sim_->renderFrame(0), refA = sim_->renderReference('A');
  cv::Mat diff;
  cv::subtract(frame0, refA, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, sd;
  cv::meanStdDev(diff.reshape(1), mean, sd);
  // Two independent N(0, 2^2) draws, each rounded: SD sqrt(2 * (4 + 1/12)) = 2.86 (clamping at
  // 0/255 is rare in this scene); 0.3 allows for the few clamped pixels.
  EXPECT_NEAR(sd[0], 2.86, 0.3);
  EXPECT_NEAR(mean[0], 0.0, 0.05);
}

TEST_F(SceneSimulatorTest, OtherSeedChangesOnlyTheNoise) {
  SimulationOptions o = sim_->options();
  o.seed = 2;
  o.preset = "static";
  o.size = {320, 240};
  SceneSimulator other(o);
  o.seed = 1;
  SceneSimulator same(o);
  const cv::Mat a = same.renderFrame(3), b = other.renderFrame(3);
  EXPECT_EQ(cv::norm(a, same.renderFrame(3), cv::NORM_INF), 0.0);
  cv::Mat diff;
  cv::subtract(a, b, diff, cv::noArray(), CV_32F);
  cv::Scalar mean, sd;
  cv::meanStdDev(diff.reshape(1), mean, sd);
  EXPECT_NEAR(sd[0], 2.86, 0.3);  // as above: only the noise differs
}

TEST_F(SceneSimulatorTest, MotionBlurSmearsMovingFrames) {
  SimulationOptions o;
  o.preset = "rotate";
  o.frames = 30;  // 40 deg in 7.5 frames: ~5 deg per frame, strong blur
  o.noiseSigma = 0.0;
  o.size = {320, 240};
  o.blur = true;
  SceneSimulator blurred(o);
  auto sharpness = [](const cv::Mat& image) {
    cv::Mat grey, lap;
    cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
    cv::Laplacian(grey, lap, CV_32F);
    cv::Scalar mean, sd;
    cv::meanStdDev(lap, mean, sd);
    return sd[0];
  };
  // Without noise the unblurred frame is the single render at the frame's pose.
  const double s = sharpness(blurred.renderView(blurred.framePose(4), 0, 0.0));
  const double b = sharpness(blurred.renderFrame(4));
  EXPECT_LT(b, 0.6 * s) << "sharp " << s << " blurred " << b;
  std::cout << "Laplacian SD sharp " << s << ", blurred " << b << "\n";
}

TEST_F(SceneSimulatorTest, RejectsBadRequests) {
  EXPECT_THROW(sim_->framePose(-1), Error);
  EXPECT_THROW(sim_->framePose(30), Error);
  EXPECT_THROW(sim_->renderReference('C'), Error);
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  R(0, 0) = std::nan("");
  EXPECT_THROW(sim_->renderDepth(RigidPose(R, Eigen::Vector3d::Zero())), Error);
  SimulationOptions bad;
  bad.frames = 0;
  EXPECT_THROW(SceneSimulator{bad}, Error);
}

TEST(SceneSimulatorEffects, WebcamEffectsLeaveTheGroundTruthExact) {
  const std::unique_ptr<render::GlContext> context = render::createHeadlessContext();
  SimulationOptions clean;
  clean.frames = 4;
  clean.size = {160, 120};
  SimulationOptions webcam = clean;
  webcam.effects = cameraEffectsFor("webcam", webcam.size);
  webcam.effects.groupFrames = 2;
  SceneSimulator a(clean), b(webcam);
  for (int k = 0; k < clean.frames; ++k) {
    EXPECT_TRUE(a.framePose(k).matrix4().isApprox(b.framePose(k).matrix4(), 0.0)) << k;
    const cv::Mat frame = b.renderFrame(k);
    ASSERT_EQ(frame.size(), clean.size);
    ASSERT_EQ(frame.type(), CV_8UC3);
  }
  for (int i = 0; i < 2; ++i)
    EXPECT_TRUE(a.referencePoses()[i].matrix4().isApprox(b.referencePoses()[i].matrix4(), 0.0));
  // The photo print lies on the desk in the reference views: the images differ there.
  EXPECT_GT(cv::norm(a.renderReferenceView(0), b.renderReferenceView(0), cv::NORM_L1),
            10.0 * clean.size.area());
}
