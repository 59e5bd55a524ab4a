#include "app/research/sixdof/PerFramePeerPoses.hpp"

#include <gtest/gtest.h>

#include <cstdio>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "app/research/baselines/PerFramePnpPeer.hpp"
#include "app/research/sixdof/GroundTruthBenchmark.hpp"

namespace reftrack::app {
namespace {

// What `bench-real --suite` relies on to replay a peer's poses in every order: on real frames
// (the ViSP desk clip, frames 0-7, references 0 and 7), each frame's pose is the same bit for bit
// whether the frames come in order (computePeerPoses) or backwards, one peer object answering
// them all. The poses are those of a working pipeline: measured ORB + PnP on these frames
// 0.05-0.13 px from the truth (the suite's visp cube); bound 1 px, while a peer that mixed frames
// up or ignored the references' poses would be tens of pixels off.
TEST(PerFramePeerPoses, APeerGivesAFrameTheSamePoseInAnyOrder) {
  const auto data = test::sharedDataDir();
  const auto visp = data ? *data / "visp-desk-apriltags" : std::filesystem::path();
  if (!data || !std::filesystem::is_directory(visp / "frames"))
    GTEST_SKIP() << "../shared/data/visp-desk-apriltags not available (the shared recordings)";
  GroundTruthSequenceSpec spec;
  spec.input = (visp / "frames").string();
  spec.camera = (visp / "camera.yml").string();
  spec.groundTruth = (visp / "groundtruth.txt").string();
  spec.frames = 8;
  const GroundTruthSequence s = loadGroundTruthSequence(spec);
  int reported = 0;
  const PeerPoses poses = computePeerPoses("orb", s, {0, 7}, [&](int done, int total) {
    EXPECT_EQ(total, 8);
    reported = done;
  });
  EXPECT_EQ(reported, 8);
  EXPECT_EQ(poses.method, "ORB+PnP");
  EXPECT_TRUE(poses.modelError.empty());
  EXPECT_GT(poses.modelPoints, 50);
  ASSERT_EQ(poses.poses.size(), 8u);
  ASSERT_EQ(poses.cpuMs.size(), 8u);
  const PerFramePnpPeer peer("orb", s.camera, {s.frames[0], s.frames[7]},
                             {*s.truth[0], *s.truth[7]});
  const std::vector<Eigen::Vector3d> cube = cubeOn({0.18, 0.12, 0}, 0.1);
  for (int k = 7; k >= 0; --k) {
    const std::size_t i = static_cast<std::size_t>(k);
    const std::optional<RigidPose> again = peer.locate(s.frames[i]).worldToCamera;
    ASSERT_TRUE(poses.poses[i]) << k << ": " << poses.reasons[i];
    ASSERT_TRUE(again) << k;
    EXPECT_TRUE(poses.poses[i]->rotation() == again->rotation()) << k;
    EXPECT_TRUE(poses.poses[i]->translation() == again->translation()) << k;
    const double error = cubeErrorPx(s.camera, cube, *s.truth[i], *poses.poses[i]);
    std::printf("frame %d: ORB+PnP cube error %.3f px\n", k, error);
    EXPECT_LT(error, 1.0) << k;
  }
}

// References that give the peer no model (blank images): every frame without a pose, the reason
// naming why; an unknown detector is an error.
TEST(PerFramePeerPoses, NoModelLeavesEveryFrameWithoutAPose) {
  GroundTruthSequence s;
  Eigen::Matrix3d K;
  K << 100, 0, 31.5, 0, 100, 23.5, 0, 0, 1;
  s.camera = PinholeCamera(K, cv::Size(64, 48));
  for (int k = 0; k < 3; ++k) {
    s.frames.emplace_back(48, 64, CV_8UC3, cv::Scalar(90, 90, 90));
    s.truth.push_back(RigidPose(Eigen::Matrix3d::Identity(), Eigen::Vector3d(0.1 * k, 0, 1)));
  }
  const PeerPoses p = computePeerPoses("akaze", s, {0, 2});
  EXPECT_EQ(p.method, "AKAZE+PnP");
  EXPECT_EQ(p.modelPoints, 0);
  EXPECT_NE(p.modelError.find("fewer than the 6 PnP needs"), std::string::npos) << p.modelError;
  ASSERT_EQ(p.poses.size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_FALSE(p.poses[k]);
    EXPECT_EQ(p.reasons[k], "no model: " + p.modelError);
  }
  EXPECT_NE(test::errorMessage([&] {
              computePeerPoses("surf", s, {0, 2});
            }).find("'surf'"),
            std::string::npos);
  s.truth[2].reset();
  EXPECT_NE(test::errorMessage([&] {
              computePeerPoses("orb", s, {0, 2});
            }).find("reference frame 2 is not a frame of the sequence with a true pose"),
            std::string::npos);
}

}  // namespace
}  // namespace reftrack::app
