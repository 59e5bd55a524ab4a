// ScenePlacement: the default object stands on the map's dominant plane. Measured on the tracker
// tests' plane world (a textured plane of known normal, its map triangulated from two rendered
// references) with clutter and noise added, and on bad input.
#include "engine/mapping/ScenePlacement.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "ErrorMessage.hpp"
#include "engine/core/Error.hpp"
#include "engine/reference/MultiReferenceMap.hpp"
#include "engine/tracking/PlaneWorld.hpp"

namespace reftrack {
namespace {

constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

struct WorldPlane {
  Eigen::Vector3d normal;  // unit, towards camera A
  double offset;           // normal . x = offset
};

// The plane world's plane (n . X_A = d in camera A's frame) in the world frame.
WorldPlane worldPlane(const test::PlaneWorld& world) {
  const Eigen::Matrix3d R = world.T_A.rotation();
  const Eigen::Vector3d t = world.T_A.translation();
  WorldPlane p{R.transpose() * world.n, world.d - world.n.dot(t)};
  const Eigen::Vector3d cameraA = world.T_A.inverse().translation();
  if (p.normal.dot(cameraA) < p.offset) p = {-p.normal, -p.offset};
  return p;
}

// The map of the plane world with every point moved by N(0, sigma) per axis, plus `clutter`
// points: a 'mug' (a cylinder 3-8 cm tall beside the middle, on the cameras' side) and points
// scattered far behind the plane (a wall seen past the desk's edge).
MultiReferenceMap noisyClutteredMap(const test::PlaneWorld& world, double sigma, int clutter) {
  MultiReferenceMap map = MultiReferenceMap::fromPair(world.map());
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, sigma);
  for (MapPoint& p : map.points) p.world += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const WorldPlane plane = worldPlane(world);
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
  for (const MapPoint& p : map.points) middle += p.world;
  middle /= static_cast<double>(map.points.size());
  const Eigen::Vector3d u = plane.normal.unitOrthogonal(), v = plane.normal.cross(u);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < clutter; ++i) {
    MapPoint p;
    if (i % 2 == 0) {
      const double angle = 2 * M_PI * unit(rng), height = 0.03 + 0.05 * unit(rng);
      p.world = middle + 0.05 * u + 0.04 * (std::cos(angle) * u + std::sin(angle) * v) +
                height * plane.normal;
    } else {
      p.world = middle + (unit(rng) - 0.5) * 0.4 * u + (unit(rng) - 0.5) * 0.4 * v -
                (0.3 + 0.5 * unit(rng)) * plane.normal;
    }
    map.points.push_back(p);
  }
  return map;
}

// 1 mm noise (the desk clip's triangulated points scatter about that much at 0.3 m) and as many
// clutter points as a third of the plane's: the plane, its side and the base are found.
TEST(ScenePlacement, StandsOnTheDominantPlaneFacingTheCameras) {
  const test::PlaneWorld world;
  const MultiReferenceMap clean = MultiReferenceMap::fromPair(world.map());
  const int planePoints = static_cast<int>(clean.points.size());
  ASSERT_GT(planePoints, 60);
  const MultiReferenceMap map = noisyClutteredMap(world, 0.001, planePoints / 3);
  const ScenePlacement s = placeOnDominantPlane(map);
  const WorldPlane truth = worldPlane(world);
  const Eigen::Vector3d up = s.rotation.col(2);
  const double angleDeg = std::acos(std::min(1.0, up.dot(truth.normal))) * kRadToDeg;
  const double baseOffPlaneMm = std::abs(truth.normal.dot(s.base) - truth.offset) * 1e3;
  std::cout << planePoints << " plane points + " << planePoints / 3 << " clutter: normal off by "
            << angleDeg << " deg, base " << baseOffPlaneMm << " mm off the plane, " << s.planePoints
            << " of " << s.consideredPoints << " considered points on it (band "
            << s.planeThresholdMetres * 1e3 << " mm, rms " << s.planeRmsMetres * 1e3
            << " mm), edge " << s.edge << " m\n";
  // Least squares over >= 30 points of 1 mm noise spread over ~0.3 m: the normal within
  // ~1mm/0.3m/sqrt(30) = 0.03 deg; 0.5 deg would mean clutter pulled the fit.
  EXPECT_LT(angleDeg, 0.5);
  // The base is on the fitted plane: the fit's offset error, ~1 mm / sqrt(30); 1 mm bound.
  EXPECT_LT(baseOffPlaneMm, 1.0);
  EXPECT_LT(s.planeRmsMetres, 0.002);  // N(0, 1 mm) per axis: 1 mm along the normal
  // The base is in the middle of the plane's points: on the plane, within a quarter of their
  // median distance from their mean (the nearest half of the points around the median of all,
  // clutter included, is what the base is the mean of).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const MapPoint& p : clean.points) mean += p.world;
  mean /= planePoints;
  std::vector<double> radii;
  for (const MapPoint& p : clean.points) radii.push_back((p.world - mean).norm());
  std::nth_element(radii.begin(), radii.begin() + planePoints / 2, radii.end());
  const double spread = radii[planePoints / 2];
  std::cout << "plane points' median distance from their mean " << spread << " m; base "
            << (s.base - mean).norm() << " m from it\n";
  EXPECT_LT((s.base - mean).norm(), 0.25 * spread);
  // A right-handed frame, its x the world x laid onto the plane.
  EXPECT_TRUE((s.rotation.transpose() * s.rotation).isIdentity(1e-12));
  EXPECT_NEAR(s.rotation.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(s.rotation.col(0).dot(up.cross(Eigen::Vector3d::UnitX())), 0.0, 1e-12);
  EXPECT_GT(s.rotation(0, 0), 0.0);
  // The edge: one of 1, 2, 5 x 10^k.
  const double mantissa = s.edge / std::pow(10.0, std::floor(std::log10(s.edge) + 1e-9));
  EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 ||
              std::abs(mantissa - 5) < 1e-9)
      << s.edge;
}

// Seen from the other side, the up axis turns with the cameras.
TEST(ScenePlacement, UpFollowsTheCamerasSide) {
  std::vector<Eigen::Vector3d> points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(-0.2, 0.2);
  for (int i = 0; i < 100; ++i) points.emplace_back(coord(rng), coord(rng), 0.0);
  const ScenePlacement above = placeOnDominantPlane(points, {{0.0, 0.0, 0.5}});
  const ScenePlacement below = placeOnDominantPlane(points, {{0.1, 0.0, -0.5}});
  EXPECT_GT(above.rotation(2, 2), 0.999999);
  EXPECT_LT(below.rotation(2, 2), -0.999999);
  EXPECT_LT(above.base.norm(), 0.1);
  EXPECT_NEAR(above.base.z(), 0.0, 1e-12);
  // The nearest half of a uniform 0.4 m square is about a disc of radius 0.16 m, whose median
  // radius is 0.11 m: rounded, 0.1 m.
  EXPECT_DOUBLE_EQ(above.edge, 0.1);
  EXPECT_TRUE(above.rotation.isIdentity(1e-9));
}

TEST(ScenePlacement, RefusesTooFewPointsAndAPlanelessCloud) {
  const std::vector<Eigen::Vector3d> few(11, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(test::errorMessage([&] { placeOnDominantPlane(few, {}); }),
            "scene placement: 11 finite map points, at least 12 are needed to find the scene's "
            "plane");
  std::vector<Eigen::Vector3d> ball;
  std::mt19937 rng(5);
  std::normal_distribution<double> coord(0.0, 0.2);
  for (int i = 0; i < 400; ++i) ball.emplace_back(coord(rng), coord(rng), coord(rng));
  EXPECT_NE(test::errorMessage([&] {
              placeOnDominantPlane(ball, {});
            }).find("no plane holds a quarter of the 200 map points"),
            std::string::npos);
  const std::vector<Eigen::Vector3d> same(20, Eigen::Vector3d(1, 2, 3));
  EXPECT_THROW(placeOnDominantPlane(same, {}), Error);
}

}  // namespace
}  // namespace reftrack
