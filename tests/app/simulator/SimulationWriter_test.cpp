#include "app/simulator/SimulationWriter.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/TumTrajectory.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {
SimulationOptions smallRun() {
  SimulationOptions o;
  o.frames = 4;
  o.size = {160, 120};
  o.seed = 9;
  o.fps = 25.0;
  return o;
}
}  // namespace

TEST(SimulationWriter, WritesACompleteRoundTrippingSequence) {
  const auto context = render::createHeadlessContext();
  SceneSimulator sim(smallRun());
  const fs::path dir = test::freshTempDir("SimulationWriter_Complete");
  // Left over from a longer earlier run: removed. Unrelated files are kept.
  fs::create_directories(dir / "frames");
  std::ofstream(dir / "frames" / "000009.png") << "stale";
  std::ofstream(dir / "frames" / "notes.txt") << "mine";
  writeSimulation(sim, dir);

  for (int k = 0; k < 4; ++k) {
    char name[16];
    std::snprintf(name, sizeof name, "%06d.png", k);
    const cv::Mat frame = cv::imread((dir / "frames" / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(frame.size(), cv::Size(160, 120)) << name;
    ASSERT_EQ(frame.type(), CV_8UC3);
    // PNG is lossless: the file holds exactly the simulator's frame.
    EXPECT_EQ(cv::norm(frame, sim.renderFrame(k), cv::NORM_INF), 0.0) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "frames" / "000009.png"));
  EXPECT_TRUE(fs::exists(dir / "frames" / "notes.txt"));
  for (const auto& entry : fs::directory_iterator(dir / "frames"))
    EXPECT_NE(entry.path().filename().string().rfind(".tmp", 0), 0u) << "temporary file left";

  const PinholeCamera camera = PinholeCamera::load(dir / "camera.yml");
  EXPECT_EQ(camera.imageSize(), cv::Size(160, 120));
  EXPECT_LT((camera.K() - sim.camera().K()).norm(), 1e-9);

  // TUM files carry 17 significant digits: poses come back to ~1e-12.
  const TumTrajectory truth = TumTrajectory::load(dir / "groundtruth.txt");
  ASSERT_EQ(truth.poses.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(truth.poses[k].timestamp, k / 25.0, 1e-6);
    EXPECT_LT((truth.poses[k].worldToCamera.matrix4() - sim.framePose(k).matrix4()).norm(), 1e-9);
  }
  const TumTrajectory refs = TumTrajectory::load(dir / "references.txt");
  ASSERT_EQ(refs.poses.size(), 2u);
  EXPECT_TRUE(fs::exists(dir / "reference_00.png"));
  EXPECT_TRUE(fs::exists(dir / "reference_01.png"));
  EXPECT_LT((refs.poseAt(0.0)->matrix4() - sim.referencePoseA().matrix4()).norm(), 1e-9);
  EXPECT_LT((refs.poseAt(1.0)->matrix4() - sim.referencePoseB().matrix4()).norm(), 1e-9);
  EXPECT_EQ(cv::norm(cv::imread((dir / "reference_b.png").string()), sim.renderReference('B'),
                     cv::NORM_INF),
            0.0);

  cv::FileStorage scene((dir / "scene.yml").string(), cv::FileStorage::READ);
  ASSERT_TRUE(scene.isOpened());
  EXPECT_EQ(static_cast<std::string>(scene["marker_dictionary"]), "DICT_6X6_250");
  EXPECT_EQ(static_cast<int>(scene["marker_id"]), 23);
  EXPECT_DOUBLE_EQ(static_cast<double>(scene["marker_side_m"]), 0.2);
  EXPECT_EQ(static_cast<std::string>(scene["preset"]), "handheld");
  EXPECT_EQ(static_cast<std::string>(scene["seed"]), "9");
  EXPECT_EQ(static_cast<int>(scene["frame_count"]), 4);
  EXPECT_EQ(static_cast<int>(scene["image_width"]), 160);
  EXPECT_EQ(static_cast<int>(scene["image_height"]), 120);
  EXPECT_DOUBLE_EQ(static_cast<double>(scene["fps"]), 25.0);
}

TEST(SimulationWriter, UnwritableFolderIsAClearError) {
  const auto context = render::createHeadlessContext();
  SimulationOptions o = smallRun();
  o.frames = 1;
  SceneSimulator sim(o);
  const fs::path dir = test::freshTempDir("SimulationWriter_Unwritable");
  std::ofstream(dir / "file") << "a file, not a folder";
  try {
    writeSimulation(sim, dir / "file" / "out");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create output folder"), std::string::npos)
        << e.what();
  }
}

TEST(SimulationWriter, WritesEveryReferenceViewAndItsPose) {
  const auto context = render::createHeadlessContext();
  SimulationOptions o = smallRun();
  o.preset = "walkaround";
  o.frames = 2;
  SceneSimulator sim(o);
  ASSERT_EQ(sim.referencePoses().size(), 6u);  // the walkaround default
  const fs::path dir = test::freshTempDir("SimulationWriter_References");
  std::ofstream(dir / "reference_07.png") << "stale";  // from a run with more references
  writeSimulation(sim, dir);
  const TumTrajectory refs = TumTrajectory::load(dir / "references.txt");
  ASSERT_EQ(refs.poses.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "reference_%02d.png", i);
    EXPECT_NEAR(refs.poses[i].timestamp, i, 1e-9);
    EXPECT_LT((refs.poses[i].worldToCamera.matrix4() - sim.referencePoses()[i].matrix4()).norm(),
              1e-9)
        << i;
    const cv::Mat image = cv::imread((dir / name).string(), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(image.size(), cv::Size(160, 120)) << name;
    EXPECT_EQ(cv::norm(image, sim.renderReferenceView(i), cv::NORM_INF), 0.0) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "reference_07.png"));
  // The two-reference layout stays: A and B are views 0 and 1.
  EXPECT_EQ(cv::norm(cv::imread((dir / "reference_a.png").string()), sim.renderReferenceView(0),
                     cv::NORM_INF),
            0.0);
  EXPECT_EQ(cv::norm(cv::imread((dir / "reference_b.png").string()), sim.renderReferenceView(1),
                     cv::NORM_INF),
            0.0);
  cv::FileStorage scene((dir / "scene.yml").string(), cv::FileStorage::READ);
  EXPECT_EQ(static_cast<int>(scene["reference_count"]), 6);
}

// A lens given in the options reaches camera.yml, the file every command reads.
TEST(SimulationWriter, CameraFileCarriesTheLensDistortion) {
  const auto context = render::createHeadlessContext();
  SimulationOptions o = smallRun();
  o.frames = 1;
  o.fovDeg = 50.0;
  o.distortion = {-0.3, 0.05, 0.001, -0.002, 0.0};
  SceneSimulator sim(o);
  const fs::path dir = test::freshTempDir("SimulationWriter_Distortion");
  writeSimulation(sim, dir);
  const PinholeCamera camera = PinholeCamera::load(dir / "camera.yml");
  ASSERT_EQ(camera.distortion().size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_DOUBLE_EQ(camera.distortion()[i], o.distortion[i]);
}
