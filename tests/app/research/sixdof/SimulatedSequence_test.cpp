#include "app/research/sixdof/SimulatedSequence.hpp"

#include <gtest/gtest.h>

#include "TestPaths.hpp"
#include "app/simulator/SceneSimulator.hpp"
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

// The walkaround's N-reference map: every reference view, posed by the marker to within the
// marker's accuracy, points shared by neighbouring views; the cache keeps it (one folder per
// reference count) and a two-reference request does not prepare it.
TEST(SimulatedSequence, PreparesAndCachesTheMapOfAllReferences) {
  const auto gl = render::createHeadlessContext();
  const std::filesystem::path cache = test::freshTempDir("simulated_sequence_references");
  SimulationOptions o;
  o.preset = "walkaround";
  o.frames = 2;
  o.references = 4;
  const SimulatedSequence made = cachedSimulatedSequence(o, cache, SequenceMaps::AllReferences);
  ASSERT_TRUE(made.references);
  ASSERT_EQ(made.references->size(), 4);
  SceneSimulator sim(o);
  for (int i = 0; i < 4; ++i) {
    // Marker poses of the simulator's references: within 1 mm and 0.1 deg (SceneSimulator test
    // measures 0.07 mm and 0.03 deg at worst).
    const RigidPose& truth = sim.referencePoses()[static_cast<std::size_t>(i)];
    EXPECT_LT(RigidPose::translationDistance(made.references->views[i].T, truth), 0.001) << i;
    EXPECT_LT(RigidPose::rotationDistance(made.references->views[i].T, truth), 0.1 * M_PI / 180)
        << i;
  }
  // A and B (0.25 m apart) and A and view 2 (30 deg apart) share points.
  EXPECT_GT(made.references->sharedPoints(0, 1), 100);
  EXPECT_GT(made.references->sharedPoints(0, 2), 30);
  std::cout << "map of 4: " << made.references->points.size() << " points, shared 0-1 "
            << made.references->sharedPoints(0, 1) << ", 0-2 "
            << made.references->sharedPoints(0, 2) << ", 1-3 "
            << made.references->sharedPoints(1, 3) << "\n";
  const SimulatedSequence loaded = cachedSimulatedSequence(o, cache, SequenceMaps::AllReferences);
  ASSERT_TRUE(loaded.references);
  EXPECT_EQ(loaded.references->points.size(), made.references->points.size());
  EXPECT_FALSE(cachedSimulatedSequence(o, cache).references);
}

}  // namespace
}  // namespace reftrack::app
