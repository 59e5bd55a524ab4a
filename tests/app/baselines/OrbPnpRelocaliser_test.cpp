#include "app/baselines/OrbPnpRelocaliser.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/relocalisation/RelocalisationTestScene.hpp"

namespace reftrack::app {
namespace {

// The baseline must be a working relocaliser, or the benchmark ratio means nothing: on the
// synthetic room corner it finds views near the references to a centimetre (OpenCV's default
// 8 px RANSAC threshold, no refinement), and nothing on a black frame.
TEST(OrbPnpRelocaliser, LocatesViewsOfTheMappedSceneAndNothingOnABlackFrame) {
  const test::CornerWorld world;
  const MultiReferenceMap map = test::cornerWorldMap(world, 4, RelocalisationParams{});
  const OrbPnpRelocaliser baseline(map);
  EXPECT_GT(baseline.modelPoints(), 1000);
  const std::vector<RigidPose> views = test::randomViews(6, 4, 5);
  int found = 0;
  for (std::size_t i = 0; i < views.size(); ++i) {
    const std::optional<RigidPose> T =
        baseline.locate(world.render(views[i], 40 + static_cast<int>(i)));
    if (!T) continue;
    ++found;
    EXPECT_LT((T->cameraCentre() - views[i].cameraCentre()).norm(), 0.05) << i;
  }
  EXPECT_GE(found, 4);
  EXPECT_FALSE(baseline.locate(cv::Mat::zeros(world.size, CV_8U)));
}

TEST(OrbPnpRelocaliser, NeedsAnOrbLayer) {
  const test::CornerWorld world;
  MultiReferenceMap map = test::cornerWorldMap(world, 2, RelocalisationParams{});
  map.keypointKind = "sift";
  EXPECT_THROW(OrbPnpRelocaliser{map}, Error);
}

}  // namespace
}  // namespace reftrack::app
