// runViewer headless: one recorded frame per processed frame, a replayed trajectory written back
// unchanged, screenshots of the canvas, and clean errors before any output is written.
#include "app/viewer/ViewerApp.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "TestPaths.hpp"
#include "app/simulator/SceneSimulator.hpp"
#include "app/simulator/SimulationWriter.hpp"
#include "engine/core/Error.hpp"
#include "engine/geometry/TumTrajectory.hpp"

using namespace reftrack;
using namespace reftrack::app;
namespace fs = std::filesystem;

namespace {

int decodedFrames(const fs::path& file) {
  cv::VideoCapture capture(file.string(), cv::CAP_FFMPEG);
  int n = 0;
  cv::Mat image;
  while (capture.read(image)) ++n;
  return n;
}

ViewerOptions simOptions(int frames) {
  ViewerOptions o;
  o.input = "sim:orbit";
  o.headless = true;
  o.maxFrames = frames;
  o.source.simFrames = 20;
  o.source.simSize = {160, 120};
  return o;
}

}  // namespace

TEST(ViewerApp, HeadlessRecordsOneFramePerProcessedFrame) {
  const fs::path dir = test::freshTempDir("ViewerApp_Record");
  ViewerOptions o = simOptions(6);
  o.record = dir / "out.mp4";
  o.screenshot = dir / "last.png";
  const ViewerRunSummary s = runViewer(o);
  EXPECT_EQ(s.framesProcessed, 6);
  EXPECT_EQ(s.recording, o.record);
  EXPECT_EQ(decodedFrames(o.record), 6);
  const cv::Mat shot = cv::imread(o.screenshot.string());
  EXPECT_EQ(shot.size(), cv::Size(160, 120));  // without --ui the canvas is the frame
  // The replayed ground truth is written back: 6 poses, 1/30 s apart.
  const TumTrajectory t = TumTrajectory::load(s.trajectory);
  ASSERT_EQ(t.poses.size(), 6u);
  EXPECT_NEAR(t.poses[5].timestamp, 5 / 30.0, 1e-6);
}

TEST(ViewerApp, ImageFolderWithPosesAndCamera) {
  const fs::path dir = test::freshTempDir("ViewerApp_Folder");
  {
    const auto context = render::createHeadlessContext();
    SimulationOptions sim;
    sim.preset = "handheld";
    sim.frames = 4;
    sim.size = {160, 120};
    SceneSimulator simulator(sim);
    writeSimulation(simulator, dir / "seq");
  }
  ViewerOptions o;
  o.input = (dir / "seq" / "frames").string();
  o.camera = dir / "seq" / "camera.yml";
  o.poses = dir / "seq" / "groundtruth.txt";
  o.headless = true;
  o.record = dir / "out.mp4";
  const ViewerRunSummary s = runViewer(o);
  EXPECT_EQ(s.framesProcessed, 4);  // the whole folder
  const TumTrajectory truth = TumTrajectory::load(o.poses),
                      replay = TumTrajectory::load(s.trajectory);
  ASSERT_EQ(replay.poses.size(), 4u);
  for (int k = 0; k < 4; ++k)
    EXPECT_LT(
        RigidPose::translationDistance(replay.poses[k].worldToCamera, truth.poses[k].worldToCamera),
        1e-9);
}

TEST(ViewerApp, BadInputFailsBeforeWritingOutputs) {
  const fs::path dir = test::freshTempDir("ViewerApp_Bad");
  ViewerOptions o = simOptions(2);
  o.record = dir / "out.mp4";
  o.input = "sim:nowhere";
  EXPECT_THROW(runViewer(o), Error);
  o = simOptions(2);
  o.maxFrames = 0;
  EXPECT_THROW(runViewer(o), Error);
  o = simOptions(2);
  o.ui = true;
  o.headless = false;
  EXPECT_THROW(runViewer(o), Error);  // --ui is a headless option
  o = simOptions(2);
  o.screenshot = dir / "shot.jpg";
  EXPECT_THROW(runViewer(o), Error);
  EXPECT_TRUE(fs::is_empty(dir));
}
