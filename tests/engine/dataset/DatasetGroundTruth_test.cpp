// loadGroundTruth: a TUM file as is; tum:DIR and euroc:DIR ground truth interpolated at the
// frame times, EuRoC through T_BS; clear errors when the ground truth is missing.
#include "engine/dataset/DatasetGroundTruth.hpp"

#include <gtest/gtest.h>

#include "DatasetFixtures.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

namespace {

// Uniform motion (see TrajectoryInterpolation_test): interpolation reproduces it exactly.
RigidPose poseAt(double t) {
  const Eigen::Vector3d c(0.2 * t, -0.1 * t, 0.5 + 0.05 * t);
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d(1, 2, 3).normalized()));
  return RigidPose(q, c).inverse();
}

PinholeCamera smallCamera() {
  Eigen::Matrix3d K;
  K << 40, 0, 15.5, 0, 40, 11.5, 0, 0, 1;
  return PinholeCamera(K, {32, 24});
}

}  // namespace

TEST(DatasetGroundTruth, TumGroundTruthAtTheFrameTimes) {
  const fs::path dir = test::freshTempDir("DatasetGroundTruth_tum");
  // Frames at 30 Hz from t0; motion capture at 100 Hz, starting after the first frame.
  const double t0 = 1305031102.175304;
  std::vector<double> times;
  for (int k = 0; k < 10; ++k) times.push_back(t0 + k / 30.0);
  TumTrajectory mocap;
  for (int k = 5; k < 40; ++k) mocap.poses.push_back({t0 + k / 100.0, poseAt(k / 100.0)});
  test::writeTumSequence(dir, std::vector<cv::Mat>(10, cv::Mat(24, 32, CV_8UC3)), times, mocap);
  const GroundTruth gt = loadGroundTruth("tum:" + dir.string());
  // Frame 0 (t0) and frame 1 (t0 + 0.033) precede the first sample (t0 + 0.05): no pose.
  ASSERT_EQ(gt.trajectory.poses.size(), 8u);
  for (const StampedPose& p : gt.trajectory.poses) {
    // Timestamps are the rgb.txt ones (6 decimals); poses at those times, to the interpolation's
    // exactness (1e-9 m) plus the 0.5 us rounding of the written timestamps (0.2 m/s * 0.5 us).
    const RigidPose truth = poseAt(p.timestamp - t0);
    EXPECT_LT(RigidPose::translationDistance(p.worldToCamera, truth), 1e-6);
    EXPECT_LT(RigidPose::rotationDistance(p.worldToCamera, truth), 1e-6);
  }
  EXPECT_NE(gt.description.find("35 samples interpolated at 8 of the 10 frame times"),
            std::string::npos)
      << gt.description;
  // The TUM file itself, as is.
  EXPECT_EQ(loadGroundTruth((dir / "groundtruth.txt").string()).trajectory.poses.size(), 35u);
}

TEST(DatasetGroundTruth, EurocGroundTruthIsTheCameraPoseAtTheFrameTimes) {
  const fs::path dir = test::freshTempDir("DatasetGroundTruth_euroc");
  const long long t0 = 1403636579763555584LL;
  std::vector<long long> frameNs;
  for (int k = 0; k < 6; ++k) frameNs.push_back(t0 + k * 50000000LL);  // 20 Hz
  std::vector<std::pair<long long, RigidPose>> mocap;                  // 200 Hz
  for (int k = 0; k < 60; ++k) mocap.push_back({t0 + 1000000LL + k * 5000000LL, poseAt(k * 0.005)});
  // mocap sample k is the camera pose at (t - t0 - 1 ms); the writer stores body poses through
  // T_BS, the reader must undo it.
  const RigidPose tbs(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(0, 1, 1).normalized())),
      Eigen::Vector3d(-0.02, 0.06, 0.01));
  test::writeEurocSequence(dir, std::vector<cv::Mat>(6, cv::Mat(24, 32, CV_8UC1)), frameNs,
                           smallCamera(), tbs, mocap);
  const GroundTruth gt = loadGroundTruth("euroc:" + dir.string());
  // Frame 0 precedes the first sample (t0 + 1 ms): 5 of 6 frames have a pose.
  ASSERT_EQ(gt.trajectory.poses.size(), 5u);
  for (std::size_t i = 0; i < gt.trajectory.poses.size(); ++i) {
    const StampedPose& p = gt.trajectory.poses[i];
    EXPECT_NEAR(p.timestamp, (t0 + static_cast<long long>(i + 1) * 50000000LL) * 1e-9, 3e-7);
    const RigidPose truth = poseAt((i + 1) * 0.05 - 0.001);
    // Uniform motion: exact but for the seconds held in doubles near 1.4e9 (2.4e-7 s apart):
    // the interpolation weight over 5 ms is off by up to 5e-5, i.e. 6e-8 m at 0.23 m/s.
    EXPECT_LT(RigidPose::translationDistance(p.worldToCamera, truth), 1e-6) << i;
    EXPECT_LT(RigidPose::rotationDistance(p.worldToCamera, truth), 1e-6) << i;
  }
}

TEST(DatasetGroundTruth, MissingGroundTruthIsAClearError) {
  const fs::path dir = test::freshTempDir("DatasetGroundTruth_missing");
  test::writeTumSequence(dir, {cv::Mat(24, 32, CV_8UC3)}, {1.0}, {});
  test::writeEurocSequence(dir / "euroc", {cv::Mat(24, 32, CV_8UC1)}, {1000}, smallCamera(),
                           RigidPose(), {});
  auto errorOf = [](const std::string& spec) {
    try {
      loadGroundTruth(spec);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(errorOf("tum:" + dir.string()).find("has no groundtruth.txt"), std::string::npos);
  EXPECT_NE(errorOf("euroc:" + (dir / "euroc").string()).find("has no ground truth"),
            std::string::npos);
  // Ground truth on another clock: covers no frame time.
  TumTrajectory other;
  other.poses = {{100.0, poseAt(0)}, {100.01, poseAt(0.01)}};
  other.save(dir / "groundtruth.txt");
  EXPECT_NE(errorOf("tum:" + dir.string()).find("covers none of the frame times"),
            std::string::npos)
      << errorOf("tum:" + dir.string());
}
