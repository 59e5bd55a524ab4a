#include "app/experiments/SimulatedSequence.hpp"

#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"
#include "render/context/GlContext.hpp"

namespace reftrack::app {
namespace {

// A sequence stored by the first call is loaded by the second: the same frames (PNG is
// lossless), the same ground truth (TUM with 17 digits) and the same map.
TEST(SimulatedSequence, CacheReturnsTheSameSequenceAndRefusesABrokenFolder) {
  const auto gl = render::createHeadlessContext();
  const std::filesystem::path cache = test::freshTempDir("simulated_sequence_cache");
  SimulationOptions o;
  o.frames = 4;
  o.size = {320, 240};
  const SimulatedSequence made = cachedSimulatedSequence(o, cache);
  const SimulatedSequence loaded = cachedSimulatedSequence(o, cache);
  ASSERT_EQ(loaded.frames.size(), made.frames.size());
  for (std::size_t k = 0; k < made.frames.size(); ++k)
    EXPECT_EQ(cv::norm(made.frames[k], loaded.frames[k], cv::NORM_INF), 0.0) << k;
  ASSERT_EQ(loaded.groundTruth.poses.size(), made.groundTruth.poses.size());
  for (std::size_t k = 0; k < made.groundTruth.poses.size(); ++k)
    EXPECT_LT(RigidPose::translationDistance(made.groundTruth.poses[k].worldToCamera,
                                             loaded.groundTruth.poses[k].worldToCamera),
              1e-12);
  EXPECT_EQ(loaded.preparation.map.matches.size(), made.preparation.map.matches.size());
  EXPECT_EQ(loaded.camera.imageSize(), made.camera.imageSize());

  // Another option is another folder; a frame missing from a stored folder is a clear error.
  o.seed = 2;
  EXPECT_EQ(cachedSimulatedSequence(o, cache).frames.size(), 4u);
  std::vector<std::filesystem::path> victims;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(cache))
    if (entry.path().filename() == "000002.png") victims.push_back(entry.path());
  ASSERT_EQ(victims.size(), 2u);
  for (const auto& v : victims) std::filesystem::remove(v);
  try {
    cachedSimulatedSequence(o, cache);
    FAIL() << "a broken cache folder was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("000002.png"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace reftrack::app
