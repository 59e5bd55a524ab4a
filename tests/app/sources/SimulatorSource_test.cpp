// SimulatorSource: the simulator's frames, camera and ground truth, rendered on this thread.
#include "app/sources/SimulatorSource.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(SimulatorSource, FramesAndGroundTruthMatchTheSimulator) {
  const auto context = render::createHeadlessContext();
  SimulationOptions options;
  options.preset = "orbit";
  options.frames = 3;
  options.size = {160, 120};
  options.fps = 10.0;
  SimulatorSource source(options);
  SceneSimulator reference(options);
  EXPECT_TRUE(source.needsGlThread());
  EXPECT_EQ(source.frameCount(), 3);
  EXPECT_EQ(source.camera().imageSize(), cv::Size(160, 120));
  const TumTrajectory truth = source.groundTruth();
  ASSERT_EQ(truth.poses.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    const auto frame = source.next();
    ASSERT_TRUE(frame);
    EXPECT_EQ(frame->index, k);
    EXPECT_DOUBLE_EQ(frame->timestamp, k / 10.0);
    EXPECT_DOUBLE_EQ(truth.poses[k].timestamp, k / 10.0);
    // Deterministic in (seed, k): byte-identical to the simulator's own render.
    EXPECT_EQ(cv::norm(frame->image, reference.renderFrame(k), cv::NORM_INF), 0.0);
    EXPECT_LT(RigidPose::translationDistance(truth.poses[k].worldToCamera, reference.framePose(k)),
              1e-12);
  }
  EXPECT_FALSE(source.next());
  source.seek(2);
  EXPECT_EQ(source.next()->index, 2);
  EXPECT_THROW(source.seek(3), Error);
}
