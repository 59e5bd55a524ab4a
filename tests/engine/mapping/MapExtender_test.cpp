#include "engine/mapping/MapExtender.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "engine/tracking/PlaneWorld.hpp"

namespace reftrack {
namespace {

using test::pathPose;
using test::PlaneWorld;

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// The tracker's plane world (exact homographies): a camera moving 0.27 m and 11 degrees away
// from reference A over 80 frames, references added every ~8 cm. Truth: world->camera of frame k
// = pathPose(k) * T_A.
TEST(MapExtender, AddsReferencesAlongAPathOutOfTheMapAtTheirTruePoses) {
  const PlaneWorld world;
  const MultiReferenceMap start = MultiReferenceMap::fromPair(world.map());
  MapExtenderParams params;
  params.extension.maxDistanceMetres = 0.08;
  MapExtender extender(start, params);
  int tracked = 0;
  for (int k = 0; k <= 80; ++k) {
    const ExtensionFrame f = extender.process(world.render(pathPose(k), 300 + k), k);
    tracked += f.tracking.worldToCamera ? 1 : 0;
    if (f.added) {  // the tracked pose the reference starts from, before any adjustment
      const RigidPose truth = pathPose(k) * world.T_A;
      RecordProperty("frame" + std::to_string(k) + "_tracked_error_um",
                     static_cast<int>(RigidPose::translationDistance(
                                          f.tracking.worldToCamera->inverse(), truth.inverse()) *
                                      1e6));
    }
    EXPECT_TRUE(f.rejected.empty()) << "frame " << k << ": " << f.rejected;
  }
  const BundleAdjustmentReport final = extender.finish();
  const MultiReferenceMap& map = extender.map();
  EXPECT_EQ(tracked, 81);
  // 0.136 m per 40 frames of centre motion: beyond 8 cm about every 24 frames.
  ASSERT_GE(extender.added().size(), 2u);
  ASSERT_EQ(map.size(), 2 + static_cast<int>(extender.added().size()));
  for (int v : {0, 1}) EXPECT_EQ(map.views[v].T.matrix4(), start.views[v].T.matrix4());
  for (const AddedReference& a : extender.added()) {
    const ReferenceView& view = map.views[static_cast<std::size_t>(a.view)];
    EXPECT_FALSE(view.anchored);
    EXPECT_EQ(a.reason, ExtensionReason::Distance);
    EXPECT_GT(a.distanceMetres, 0.08);
    EXPECT_GT(a.pointsExtended, 30) << a.view;
    const RigidPose truth = pathPose(a.frameIndex) * world.T_A;
    const double mm = RigidPose::translationDistance(view.T.inverse(), truth.inverse()) * 1e3;
    const double deg = RigidPose::rotationDistance(view.T, truth) * kRadToDeg;
    // The tracker's own bound on this world is 2 mm / 0.1 degree; the adjustment must not lose
    // that (it pins the added references on the anchored pair's points).
    EXPECT_LT(mm, 2.0) << "reference " << a.view << " from frame " << a.frameIndex;
    EXPECT_LT(deg, 0.1) << "reference " << a.view << " from frame " << a.frameIndex;
    RecordProperty("reference" + std::to_string(a.view) + "_error_um", static_cast<int>(mm * 1e3));
  }
  EXPECT_TRUE(final.converged) << final.solverMessage;
  EXPECT_LT(final.finalRmsPx, 0.5);
  EXPECT_EQ(final.viewsHeld, 0);
  map.check();
}

TEST(MapExtender, RefusesAMapWithoutTwoReferences) {
  const PlaneWorld world;
  MultiReferenceMap one = MultiReferenceMap::fromPair(world.map());
  one.views.pop_back();
  one.points.clear();
  EXPECT_THROW(MapExtender(one, MapExtenderParams{}), Error);
  MapExtenderParams bad;
  bad.extension.maxAngleDeg = -1;
  EXPECT_THROW(MapExtender(MultiReferenceMap::fromPair(world.map()), bad), Error);
}

}  // namespace
}  // namespace reftrack
