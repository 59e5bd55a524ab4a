#include "app/research/sixdof/GroundTruthSequence.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "DatasetFixtures.hpp"
#include "ErrorMessage.hpp"
#include "TestPaths.hpp"

using namespace reftrack;
using namespace reftrack::app;
using reftrack::test::errorMessage;

namespace {

PinholeCamera testCamera() {
  Eigen::Matrix3d K;
  K << 300, 0, 79.5, 0, 300, 59.5, 0, 0, 1;
  return PinholeCamera(K, cv::Size(160, 120), {-0.1, 0.01, 0, 0, 0});
}

// The camera k cm to the right of the origin, looking down the world's -z from 1 m.
RigidPose poseOf(int k) {
  const Eigen::Matrix3d R = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return RigidPose(R, -R * Eigen::Vector3d(0.01 * k, 0, 1));
}

// An image folder of `frames` noise images of `size`, the camera file and a TUM ground truth
// at k / 30 s for frames `from` .. `to`.
struct FolderFixture {
  std::filesystem::path dir, frames, camera, groundTruth;
  FolderFixture(const std::string& name, int frames_, int from, int to,
                cv::Size size = cv::Size(160, 120)) {
    dir = test::freshTempDir(name);
    frames = dir / "frames";
    std::filesystem::create_directories(frames);
    cv::RNG rng(7);
    for (int k = 0; k < frames_; ++k) {
      cv::Mat image(size, CV_8UC3);
      rng.fill(image, cv::RNG::UNIFORM, 0, 255);
      char file[32];
      std::snprintf(file, sizeof file, "%06d.png", k);
      cv::imwrite((frames / file).string(), image);
    }
    camera = dir / "camera.yml";
    testCamera().save(camera);
    TumTrajectory gt;
    for (int k = from; k <= to; ++k) gt.poses.push_back({k / 30.0, poseOf(k)});
    groundTruth = dir / "groundtruth.txt";
    gt.save(groundTruth);
  }
  GroundTruthSequenceSpec spec() const {
    return {frames.string(), camera.string(), groundTruth.string(), 0};
  }
};

}  // namespace

// An image folder's frame k is at k / 30 s: the TUM file's poses land on their frames (the last,
// 4 / 30 s, a few 1e-7 s after its sample's 6-decimal time 0.133333, too), and frames outside it
// get none.
TEST(GroundTruthSequence, ReadsAnImageFolderWithItsCameraAndTumGroundTruth) {
  const FolderFixture f("GroundTruthSequence_folder", 6, 1, 4);
  const GroundTruthSequence s = loadGroundTruthSequence(f.spec());
  ASSERT_EQ(s.frames.size(), 6u);
  ASSERT_EQ(s.truth.size(), 6u);
  EXPECT_EQ(s.camera.imageSize(), cv::Size(160, 120));
  EXPECT_DOUBLE_EQ(s.camera.distortion()[0], -0.1);
  EXPECT_EQ(s.truthCount(), 4);
  EXPECT_FALSE(s.truth[0]);
  EXPECT_FALSE(s.truth[5]);
  for (int k = 1; k <= 4; ++k) {
    ASSERT_TRUE(s.truth[static_cast<std::size_t>(k)]) << k;
    // The TUM file's 6-decimal timestamps interpolate to within a micrometre of the pose.
    EXPECT_LT(RigidPose::translationDistance(*s.truth[static_cast<std::size_t>(k)], poseOf(k)),
              1e-6)
        << k;
  }
  EXPECT_NEAR(s.timestamps[3], 0.1, 1e-12);
  EXPECT_NE(s.framesDescription.find("frames"), std::string::npos) << s.framesDescription;

  GroundTruthSequenceSpec first3 = f.spec();
  first3.frames = 3;
  EXPECT_EQ(loadGroundTruthSequence(first3).frames.size(), 3u);
}

// A range of frames (firstFrame, frames): frames[k] is the input's frame firstFrame + k, with
// that frame's time and true pose (image folder: an exact seek; the frames differ, so a frame
// read from the wrong place would not equal the image on disk).
TEST(GroundTruthSequence, ReadsARangeOfFramesWithTheirOwnTimesAndPoses) {
  const FolderFixture f("GroundTruthSequence_range", 6, 0, 5);
  GroundTruthSequenceSpec range = f.spec();
  range.firstFrame = 2;
  range.frames = 3;
  const GroundTruthSequence s = loadGroundTruthSequence(range);
  EXPECT_EQ(s.firstFrame, 2);
  ASSERT_EQ(s.frames.size(), 3u);
  ASSERT_EQ(s.truth.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    EXPECT_NEAR(s.timestamps[i], (2 + k) / 30.0, 1e-12) << k;
    ASSERT_TRUE(s.truth[i]) << k;
    EXPECT_LT(RigidPose::translationDistance(*s.truth[i], poseOf(2 + k)), 1e-6) << k;
    char file[32];
    std::snprintf(file, sizeof file, "%06d.png", 2 + k);
    const cv::Mat onDisk = cv::imread((f.frames / file).string(), cv::IMREAD_COLOR);
    EXPECT_EQ(cv::norm(s.frames[i], onDisk, cv::NORM_INF), 0.0) << k;
  }
  range.frames = 0;  // to the end
  EXPECT_EQ(loadGroundTruthSequence(range).frames.size(), 4u);
  range.firstFrame = 6;
  const std::string m = errorMessage([&] { loadGroundTruthSequence(range); });
  EXPECT_NE(m.find("holds 6 frames: none from frame 6 on"), std::string::npos) << m;
}

// tum:DIR brings its own ground truth (its rgb.txt times), so --gt may be left out.
TEST(GroundTruthSequence, TumDatasetBringsItsGroundTruth) {
  const auto dir = test::freshTempDir("GroundTruthSequence_tum");
  std::vector<cv::Mat> images(3, cv::Mat(120, 160, CV_8UC3, cv::Scalar(90, 90, 90)));
  TumTrajectory gt;
  for (int k = 0; k < 3; ++k) gt.poses.push_back({100.0 + 0.05 * k, poseOf(k)});
  test::writeTumSequence(dir, images, {100.0, 100.05, 100.1}, gt);
  testCamera().save(dir / "camera.yml");
  const GroundTruthSequence s =
      loadGroundTruthSequence({"tum:" + dir.string(), (dir / "camera.yml").string(), "", 0});
  ASSERT_EQ(s.frames.size(), 3u);
  EXPECT_EQ(s.truthCount(), 3);
  EXPECT_LT(RigidPose::translationDistance(*s.truth[2], poseOf(2)), 1e-9);
}

// euroc:DIR brings both its camera (sensor.yaml) and its ground truth (body poses through T_BS),
// so neither --camera nor --gt is needed.
TEST(GroundTruthSequence, EurocDatasetBringsItsCameraAndGroundTruth) {
  const auto dir = test::freshTempDir("GroundTruthSequence_euroc");
  std::vector<cv::Mat> images(3, cv::Mat(120, 160, CV_8UC1, cv::Scalar(90)));
  const std::vector<long long> ns = {1000000000LL, 1050000000LL, 1100000000LL};
  const RigidPose sensorToBody(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix(),
                               Eigen::Vector3d(0.02, -0.01, 0.0));
  std::vector<std::pair<long long, RigidPose>> gt;
  for (int k = 0; k < 3; ++k) gt.emplace_back(ns[static_cast<std::size_t>(k)], poseOf(k));
  test::writeEurocSequence(dir, images, ns, testCamera(), sensorToBody, gt);
  const GroundTruthSequence s = loadGroundTruthSequence({"euroc:" + dir.string(), "", "", 0});
  ASSERT_EQ(s.frames.size(), 3u);
  EXPECT_EQ(s.frames[0].type(), CV_8UC3);
  EXPECT_NEAR(s.camera.fx(), 300.0, 1e-9);
  EXPECT_NE(s.cameraDescription.find("sensor.yaml"), std::string::npos) << s.cameraDescription;
  EXPECT_EQ(s.truthCount(), 3);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_LT(RigidPose::translationDistance(*s.truth[k], poseOf(static_cast<int>(k))), 1e-9);
    EXPECT_LT(RigidPose::rotationDistance(*s.truth[k], poseOf(static_cast<int>(k))), 1e-9);
  }
}

TEST(GroundTruthSequence, BadInputNamesWhatIsWrong) {
  const FolderFixture f("GroundTruthSequence_bad", 3, 0, 2);
  GroundTruthSequenceSpec spec = f.spec();
  spec.input = (f.dir / "absent").string();
  std::string m = errorMessage([&] { loadGroundTruthSequence(spec); });
  EXPECT_NE(m.find("absent' not found"), std::string::npos) << m;

  spec = f.spec();
  spec.camera = (f.dir / "nocamera.yml").string();
  m = errorMessage([&] { loadGroundTruthSequence(spec); });
  EXPECT_NE(m.find("nocamera.yml' not found"), std::string::npos) << m;

  spec = f.spec();
  spec.camera = "";
  m = errorMessage([&] { loadGroundTruthSequence(spec); });
  EXPECT_NE(m.find("brings no camera"), std::string::npos) << m;

  spec = f.spec();
  spec.groundTruth = (f.dir / "nogt.txt").string();
  m = errorMessage([&] { loadGroundTruthSequence(spec); });
  EXPECT_NE(m.find("nogt.txt' not found"), std::string::npos) << m;

  spec = f.spec();
  spec.groundTruth = "";
  m = errorMessage([&] { loadGroundTruthSequence(spec); });
  EXPECT_NE(m.find("brings no ground truth"), std::string::npos) << m;

  // The ground truth 10 s later than every frame.
  TumTrajectory late;
  late.poses.push_back({10.0, poseOf(0)});
  late.poses.push_back({10.03, poseOf(1)});
  late.save(f.dir / "late.txt");
  spec = f.spec();
  spec.groundTruth = (f.dir / "late.txt").string();
  m = errorMessage([&] { loadGroundTruthSequence(spec); });
  EXPECT_NE(m.find("check the time bases"), std::string::npos) << m;
}

TEST(GroundTruthSequence, FramesOfAnotherSizeThanTheCameraAreAnError) {
  const FolderFixture f("GroundTruthSequence_size", 2, 0, 1, cv::Size(200, 120));
  const std::string m = errorMessage([&] { loadGroundTruthSequence(f.spec()); });
  EXPECT_NE(m.find("is 200x120"), std::string::npos) << m;
  EXPECT_NE(m.find("160x120"), std::string::npos) << m;
}
