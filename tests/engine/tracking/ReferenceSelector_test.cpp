#include "engine/tracking/ReferenceSelector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "engine/core/Error.hpp"
#include "engine/geometry/LookAt.hpp"

namespace reftrack {
namespace {

// World->camera pose of a camera at `eye` looking at `target` (horizontal views: x axis in the
// z = 0 plane).
RigidPose lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  return lookAtPose(eye, target, Eigen::Vector3d(0, 0, -1));
}

// N references on an arc of radius 1 m in the z = 0 plane, `stepDeg` apart, all looking at the
// origin. Neighbours (i, i+1) share 40 map points, (i, i+2) share 20, farther pairs none; the
// points lie within 0.1 m of the origin (scene depth ~1 m).
MultiReferenceMap arcMap(int n, double stepDeg) {
  MultiReferenceMap map;
  map.camera = PinholeCamera::fromFieldOfView({640, 480}, 60.0);
  for (int i = 0; i < n; ++i) {
    const double a = i * stepDeg * CV_PI / 180.0;
    ReferenceView v;
    v.name = "reference_" + std::to_string(i) + ".png";
    v.T = lookAt(Eigen::Vector3d(std::sin(a), -std::cos(a), 0.0), Eigen::Vector3d::Zero());
    map.views.push_back(v);
  }
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  int corner = 0;
  for (int i = 0; i < n; ++i)
    for (const auto& [gap, count] : {std::pair{1, 40}, std::pair{2, 20}})
      for (int k = 0; k < count && i + gap < n; ++k)
        map.points.push_back(
            {Eigen::Vector3d(u(rng), u(rng), u(rng)), {{i, corner++}, {i + gap, corner++}}});
  return map;
}

// The camera on the arc at `deg` degrees (reference i sits at i * step), looking at the origin.
RigidPose onArc(double deg, double radius = 1.0) {
  const double a = deg * CV_PI / 180.0;
  return lookAt(radius * Eigen::Vector3d(std::sin(a), -std::cos(a), 0.0), Eigen::Vector3d::Zero());
}

TEST(ReferenceSelector, SharedPointTableMatchesTheMap) {
  const MultiReferenceMap map = arcMap(6, 15.0);
  const ReferenceSelector selector(map, {});
  for (int a = 0; a < map.size(); ++a)
    for (int b = 0; b < map.size(); ++b)
      if (a != b) {
        EXPECT_EQ(selector.sharedPoints(a, b), map.sharedPoints(a, b)) << a << " " << b;
      }
  // (i, i+1) share 40 and (i, i+2) 20 points: only neighbours reach the default 30.
  EXPECT_EQ(selector.candidatePairs().size(), 5u);
  EXPECT_NEAR(selector.sceneDepth(), 1.0, 0.1);  // points within 0.1 m of the origin, 1 m away
}

TEST(ReferenceSelector, PicksTheTwoReferencesAroundTheCamera) {
  const MultiReferenceMap map = arcMap(6, 15.0);
  const ReferenceSelector selector(map, {});
  // Between references 2 (30 deg) and 3 (45 deg): the pair (2, 3).
  EXPECT_EQ(selector.best(onArc(38.0)), (ReferencePair{2, 3}));
  EXPECT_EQ(selector.best(onArc(1.0)), (ReferencePair{0, 1}));
  EXPECT_EQ(selector.best(onArc(74.0)), (ReferencePair{4, 5}));
  // Beyond the ends the nearest pair still serves.
  EXPECT_EQ(selector.best(onArc(-30.0)), (ReferencePair{0, 1}));
  // Farther back along the same line of sight: the same pair.
  EXPECT_EQ(selector.best(onArc(38.0, 1.6)), (ReferencePair{2, 3}));
  // Pairs that share too few points are never chosen, even when both are nearest: with
  // min_shared_points above 40 no pair qualifies at all.
  ReferenceSelectionParams strict;
  strict.minSharedPoints = 41;
  EXPECT_THROW(ReferenceSelector(map, strict), Error);
  // With 20 shared points enough, (i, i+2) qualify too, but a camera between 2 and 3 still
  // prefers the neighbours.
  ReferenceSelectionParams loose;
  loose.minSharedPoints = 20;
  const ReferenceSelector looseSelector(map, loose);
  EXPECT_EQ(looseSelector.candidatePairs().size(), 9u);
  EXPECT_EQ(looseSelector.best(onArc(38.0)), (ReferencePair{2, 3}));
}

// The viewing direction counts: at reference 1's position but turned towards reference 4's
// viewing direction, the pair nearer in angle wins once the angle dominates.
TEST(ReferenceSelector, ViewingDirectionCounts) {
  const MultiReferenceMap map = arcMap(6, 15.0);
  ReferenceSelectionParams params;
  params.angleWeight = 10.0;
  const ReferenceSelector selector(map, params);
  const RigidPose atOne = onArc(15.0);
  const RigidPose turned(map.views[4].T.rotation(),
                         -map.views[4].T.rotation() * atOne.cameraCentre());
  const ReferencePair home = selector.best(atOne);
  EXPECT_TRUE(home.a == 1 || home.b == 1) << home.a << " " << home.b;
  const ReferencePair p = selector.best(turned);
  EXPECT_TRUE(p == (ReferencePair{3, 4}) || p == (ReferencePair{4, 5})) << p.a << " " << p.b;
  params.angleWeight = 0.0;  // position alone: a pair containing reference 1
  const ReferencePair q = ReferenceSelector(map, params).best(turned);
  EXPECT_TRUE(q.a == 1 || q.b == 1) << q.a << " " << q.b;
}

// Hysteresis: a camera moving along the arc switches pairs only after the new pair has been
// cheaper by the margin for switch_after_frames frames, and a camera jittering around the
// boundary between two pairs never flickers.
TEST(ReferenceSelector, HysteresisSwitchesLateAndNeverFlickers) {
  const MultiReferenceMap map = arcMap(6, 15.0);
  ReferenceSelectionParams params;
  params.switchAfterFrames = 3;
  params.switchMargin = 0.2;
  ReferenceSelector selector(map, params);
  EXPECT_FALSE(selector.current().valid());
  // Sweep from 0 to 75 degrees in 0.5 degree steps.
  std::vector<ReferencePair> used;
  int switches = 0;
  ReferencePair last;
  for (double deg = 0.0; deg <= 75.0; deg += 0.5) {
    const ReferencePair p = selector.select(onArc(deg));
    if (last.valid() && !(p == last)) {
      ++switches;
      // The switch happens only well past the boundary between the pairs.
      EXPECT_LT(selector.pairCost(p, onArc(deg)),
                (1.0 - params.switchMargin) * selector.pairCost(last, onArc(deg)))
          << deg;
      EXPECT_EQ(p.a, last.a + 1) << deg;  // one pair further along, never back
    }
    last = p;
  }
  EXPECT_EQ(switches, 4);
  EXPECT_EQ(last, (ReferencePair{4, 5}));
  // Jitter of +-1.5 degrees about reference 3 (45 degrees), where (2, 3) and (3, 4) trade
  // places as the cheapest pair: whichever is in use stays in use.
  selector.reset();
  selector.select(onArc(45.0));
  const ReferencePair first = selector.current();
  for (int k = 0; k < 100; ++k) {
    const ReferencePair p = selector.select(onArc(k % 2 ? 43.5 : 46.5));
    EXPECT_EQ(p, first) << k;
  }
  // A single frame far away does not switch either (switch_after_frames = 3) ...
  EXPECT_EQ(selector.select(onArc(70.0)), first);
  EXPECT_EQ(selector.select(onArc(45.0)), first);
  // ... but three in a row do.
  for (int k = 0; k < 2; ++k) EXPECT_EQ(selector.select(onArc(70.0)), first);
  EXPECT_EQ(selector.select(onArc(70.0)), (ReferencePair{4, 5}));
}

// best() stops scanning early; it must agree with the exhaustive minimum over every candidate
// pair, here on 60 references with all pairs up to 2 apart as candidates.
TEST(ReferenceSelector, EarlyStopAgreesWithTheExhaustiveMinimum) {
  const MultiReferenceMap map = arcMap(60, 6.0);
  ReferenceSelectionParams params;
  params.minSharedPoints = 20;
  const ReferenceSelector selector(map, params);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> deg(-20.0, 380.0), radius(0.5, 2.0);
  for (int k = 0; k < 200; ++k) {
    const RigidPose pose = onArc(deg(rng), radius(rng));
    ReferencePair exhaustive;
    double bestCost = INFINITY;
    for (const ReferencePair& p : selector.candidatePairs())
      if (selector.pairCost(p, pose) < bestCost) {
        bestCost = selector.pairCost(p, pose);
        exhaustive = p;
      }
    EXPECT_EQ(selector.best(pose), exhaustive) << k;
  }
}

TEST(ReferenceSelector, BadPairsAreRefused) {
  const MultiReferenceMap map = arcMap(4, 15.0);
  ReferenceSelector selector(map, {});
  EXPECT_THROW(selector.setCurrent({2, 1}), Error);
  EXPECT_THROW(selector.setCurrent({0, 4}), Error);
  selector.setCurrent({1, 2});
  EXPECT_EQ(selector.current(), (ReferencePair{1, 2}));
}

}  // namespace
}  // namespace reftrack
