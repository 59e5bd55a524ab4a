// End-to-end checks of `reftrack simulate` through the built binary.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "CommandTestSupport.hpp"
#include "TestPaths.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "engine/geometry/TumTrajectory.hpp"

using namespace reftrack;
namespace fs = std::filesystem;

namespace {

using test::CommandRun;

// `reftrack simulate ARGS`, run through the built binary.
CommandRun simulate(const std::string& args, const fs::path& scratch) {
  return test::runReftrack("simulate " + args, scratch);
}

}  // namespace

TEST(SimulateCommand, WritesASequenceThatRoundTrips) {
  const fs::path dir = test::freshTempDir("SimulateCommand_RoundTrip");
  const fs::path out = dir / "seq";
  const CommandRun run = simulate(
      "--preset orbit --frames 5 --size 160x120 --seed 4 --noise 1.5 --out " + out.string(), dir);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (const char* f :
       {"frames/000000.png", "frames/000001.png", "frames/000002.png", "camera.yml",
        "reference_a.png", "reference_b.png", "references.txt", "scene.yml", "groundtruth.txt"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_TRUE(fs::exists(out / "frames/000004.png"));
  EXPECT_FALSE(fs::exists(out / "frames/000005.png"));
  const PinholeCamera camera = PinholeCamera::load(out / "camera.yml");
  EXPECT_EQ(camera.imageSize(), cv::Size(160, 120));
  // 60 deg default field of view: fx = 80 / tan(30 deg).
  EXPECT_NEAR(camera.fx(), 80.0 / std::tan(M_PI / 6), 1e-9);
  const TumTrajectory truth = TumTrajectory::load(out / "groundtruth.txt");
  ASSERT_EQ(truth.poses.size(), 5u);
  const TumTrajectory refs = TumTrajectory::load(out / "references.txt");
  ASSERT_EQ(refs.poses.size(), 2u);
  // The orbit starts at reference view A; frame 1 of 5 is a quarter of the way round (75 deg).
  EXPECT_LT(
      RigidPose::translationDistance(truth.poses[0].worldToCamera, refs.poses[0].worldToCamera),
      1e-9);
  EXPECT_GT(
      RigidPose::translationDistance(truth.poses[1].worldToCamera, refs.poses[0].worldToCamera),
      0.1);
  EXPECT_NEAR(truth.poses[2].timestamp, 2.0 / 30.0, 1e-6);
}

TEST(SimulateCommand, WalkaroundWritesItsReferenceViews) {
  const fs::path dir = test::freshTempDir("SimulateCommand_Walkaround");
  const fs::path out = dir / "seq";
  const CommandRun run = simulate(
      "--preset walkaround --references 4 --frames 2 --size 160x120 --out " + out.string(), dir);
  ASSERT_EQ(run.exitCode, 0) << run.err;
  for (const char* f : {"reference_00.png", "reference_01.png", "reference_02.png",
                        "reference_03.png", "reference_a.png", "reference_b.png"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  EXPECT_FALSE(fs::exists(out / "reference_04.png"));
  EXPECT_EQ(TumTrajectory::load(out / "references.txt").poses.size(), 4u);
}

TEST(SimulateCommand, UsageErrorsExitWithTwo) {
  const fs::path dir = test::freshTempDir("SimulateCommand_Usage");
  const std::string out = " --out " + (dir / "x").string();
  EXPECT_EQ(simulate("--preset spiral" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--size 640by480" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--size 640x" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--frames 0" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--noise -1" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--references 1" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--references 17" + out, dir).exitCode, 2);
  EXPECT_EQ(simulate("--preset static", dir).exitCode, 2);  // --out missing
  EXPECT_FALSE(fs::exists(dir / "x"));
}

TEST(SimulateCommand, UnwritableOutputExitsWithOneAndAMessage) {
  const fs::path dir = test::freshTempDir("SimulateCommand_Unwritable");
  std::ofstream(dir / "file") << "not a folder";
  const CommandRun run =
      simulate("--frames 1 --size 64x48 --out " + (dir / "file" / "seq").string(), dir);
  EXPECT_EQ(run.exitCode, 1);
  EXPECT_NE(run.err.find("cannot create output folder"), std::string::npos) << run.err;
}
