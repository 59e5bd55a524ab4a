#include "engine/reference/ReferencePreparer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <functional>
#include <opencv2/imgproc.hpp>

#include "ErrorMessage.hpp"
#include "PlanarTestScene.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using reftrack::test::PlanarTestScene;

namespace {

constexpr double kPi = 3.14159265358979323846;

const MarkerSpec& marker() {
  static const MarkerSpec m = MarkerSpec::parse("DICT_6X6_250:23:0.2");
  return m;
}

// A textured plane with the marker at its centre; A 1 m above it, B 25 cm to the side.
struct MarkerScene {
  PlanarTestScene scene{&marker()};
  RigidPose T_A = PlanarTestScene::lookAt({0.05, -0.3, 0.95}, {0.0, 0.0, 0.0});
  RigidPose T_B = PlanarTestScene::lookAt({0.3, -0.25, 0.9}, {0.0, 0.0, 0.0});
  ReferenceImage a{scene.render(T_A), "view_a.png"}, b{scene.render(T_B), "view_b.png"};
};

const MarkerScene& markerScene() {
  static const MarkerScene s;
  return s;
}

cv::Mat hideMarker(const MarkerScene& s, const RigidPose& T, const cv::Mat& image) {
  cv::Mat out = image.clone();
  std::vector<cv::Point> polygon;
  for (const Eigen::Vector3d& c : marker().cornersWorld()) {
    const Eigen::Vector2d p = s.scene.camera.project(T, 1.6 * c);  // covers the white border
    polygon.emplace_back(static_cast<int>(p.x()), static_cast<int>(p.y()));
  }
  cv::fillConvexPoly(out, polygon, cv::Scalar(128));
  return out;
}

}  // namespace

TEST(ReferencePreparer, MarkerPosesAndPointsMatchTheExactPlane) {
  const MarkerScene& s = markerScene();
  const ReferencePreparer preparer(s.scene.camera);
  const Preparation p = preparer.prepare(s.a, s.b, marker());
  for (const auto& [est, truth] : {std::pair{p.map.T_A, s.T_A}, std::pair{p.map.T_B, s.T_B}}) {
    // The 0.2 m marker spans ~120 px here, seen from 30 degrees off its normal: 0.2 px of corner
    // noise tilts IPPE's solution by ~0.5 degree and moves the camera ~1 cm (measured 0.58
    // degree, 9.6 mm). The 2 mm / 0.1 degree bar is held on the simulator's scene in
    // tests/app/commands/PrepareCommand_test.cpp.
    EXPECT_LT((est.cameraCentre() - truth.cameraCentre()).norm(), 0.02);
    EXPECT_LT(RigidPose::rotationDistance(est, truth) * 180.0 / kPi, 1.0);
  }
  ASSERT_TRUE(p.report.markerRmsA && p.report.markerRmsB);
  EXPECT_LT(*p.report.markerRmsA, 0.5);  // exact homography rendering: sub-pixel corners
  EXPECT_NEAR(p.report.baselineMetres, (s.T_A.cameraCentre() - s.T_B.cameraCentre()).norm(),
              0.02);  // both camera centres are good to 1 cm (above)
  EXPECT_GE(p.map.matches.size(), 200u);
  EXPECT_GE(p.report.occupiedGridCells, 9);
  EXPECT_EQ(p.map.cornersA.size(), static_cast<size_t>(p.report.matching.cornersA));
  EXPECT_NE(p.map.poseSource.find("DICT_6X6_250:23:0.2"), std::string::npos);
  EXPECT_NE(p.map.preparationParams.find("max_epipolar_distance_px"), std::string::npos);
  // Points are in camera A's frame; the true plane is world z = 0. Through the estimated poses
  // the marker pose error (~0.5 degree over points up to 0.6 m from the axis: ~5 mm) adds to
  // triangulation noise (~1 mm at 1 m).
  // A wrong match that survives every gate lands far off the plane (measured: 1 of 401, 0.35 m,
  // a corner whose true partner was not detected in B); the tracker's PnP-RANSAC and residual
  // gate absorb such points, so up to 1% may be off by more than 2 cm, and the rest are held to
  // the accuracy above.
  double sq = 0.0;
  int onPlane = 0, offPlane = 0;
  for (const ReferenceMatch& m : p.map.matches) {
    const Eigen::Vector3d world = s.T_A.inverse() * m.pointA;
    if (std::abs(world.z()) > 0.02) {
      ++offPlane;
      continue;
    }
    sq += world.z() * world.z();
    ++onPlane;
  }
  EXPECT_LE(offPlane, static_cast<int>(p.map.matches.size()) / 100);
  ASSERT_GT(onPlane, 0);
  EXPECT_LT(std::sqrt(sq / onPlane), 0.006);
  // The whole map survives a save/load round trip.
  const auto dir = test::freshTempDir("ReferencePreparer_roundtrip");
  p.map.save(dir);
  const ReferenceMap loaded = ReferenceMap::load(dir);
  EXPECT_EQ(loaded.matches.size(), p.map.matches.size());
}

TEST(ReferencePreparer, KnownPosesAreUsedAsGiven) {
  const MarkerScene& s = markerScene();
  const Preparation p = ReferencePreparer(s.scene.camera).prepare(s.a, s.b, s.T_A, s.T_B, "given");
  EXPECT_LT(RigidPose::translationDistance(p.map.T_A, s.T_A), 1e-12);
  EXPECT_FALSE(p.report.markerRmsA.has_value());
  EXPECT_EQ(p.map.poseSource, "given");
  EXPECT_GE(p.map.matches.size(), 200u);
}

// Reference B's given pose turned 0.3 deg about the marker's normal (a fiducial's weak
// direction): with preparation.refine_given_poses the preparation refines B from the matches (on
// the correlation peaks, which every match keeps next to B's corner) and the points with it; by
// default given poses are kept (issue 24: on real clips with accurate poses refining them raised
// the error), as with refine_given_poses false.
TEST(ReferencePreparer, GivenPosesAreKeptByDefaultAndRefinedOnRequest) {
  const MarkerScene& s = markerScene();
  const RigidPose turn(
      Eigen::AngleAxisd(0.3 * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
      Eigen::Vector3d::Zero());
  const RigidPose givenB = s.T_B * turn.inverse();  // B turned about the world origin
  ReferencePreparerParams refine;
  refine.refineGivenPoses = true;
  const Preparation given =
      ReferencePreparer(s.scene.camera).prepare(s.a, s.b, s.T_A, givenB, "given");
  const Preparation refined =
      ReferencePreparer(s.scene.camera, refine).prepare(s.a, s.b, s.T_A, givenB, "given");
  EXPECT_FALSE(given.report.poseRefinement.has_value());
  EXPECT_LT(RigidPose::rotationDistance(given.map.T_B, givenB), 1e-12);
  ASSERT_TRUE(refined.report.poseRefinement.has_value());
  EXPECT_LT(RigidPose::translationDistance(refined.map.T_A, s.T_A), 1e-12);
  // Every match keeps the peak it was triangulated from, within max_peak_offset_px of B's corner.
  for (const ReferenceMatch& m : given.map.matches) {
    ASSERT_TRUE(m.peakB.has_value());
    EXPECT_FALSE(m.peakA.has_value());
    EXPECT_LE(cv::norm(*m.peakB - given.map.cornersB[static_cast<std::size_t>(m.cornerB)].pixel),
              EpipolarMatcherParams{}.maxPeakOffsetPx + 1e-4);
  }
  const auto planeRmsMm = [&](const ReferenceMap& map) {
    double sq = 0.0;
    int n = 0;
    for (const ReferenceMatch& m : map.matches) {
      const double z = (s.T_A.inverse() * m.pointA).z();
      if (std::abs(z) > 0.02) continue;  // wrong matches, as above
      sq += z * z;
      ++n;
    }
    return 1000.0 * std::sqrt(sq / std::max(n, 1));
  };
  const double turnedDeg = RigidPose::rotationDistance(given.map.T_B, s.T_B) * 180.0 / kPi;
  const double refinedDeg = RigidPose::rotationDistance(refined.map.T_B, s.T_B) * 180.0 / kPi;
  std::printf("B %.3f -> %.3f deg off; points off the plane %.2f -> %.2f mm RMS (%zu -> %zu)\n",
              turnedDeg, refinedDeg, planeRmsMm(given.map), planeRmsMm(refined.map),
              given.map.matches.size(), refined.map.matches.size());
  EXPECT_NEAR(turnedDeg, 0.3, 1e-6);
  EXPECT_LT(refinedDeg, 0.5 * turnedDeg);
  EXPECT_LT(planeRmsMm(refined.map), planeRmsMm(given.map));
}

TEST(ReferencePreparer, EachBadInputHasItsOwnMessage) {
  const MarkerScene& s = markerScene();
  const ReferencePreparer preparer(s.scene.camera);
  const ReferenceImage hiddenA{hideMarker(s, s.T_A, s.a.image), "hidden_a.png"};
  const ReferenceImage hiddenB{hideMarker(s, s.T_B, s.b.image), "hidden_b.png"};

  const std::string none =
      test::errorMessage([&] { preparer.prepare(hiddenA, hiddenB, marker()); });
  EXPECT_NE(none.find("hidden_a.png"), std::string::npos) << none;

  const std::string oneOnly = test::errorMessage([&] { preparer.prepare(s.a, hiddenB, marker()); });
  EXPECT_NE(oneOnly.find("hidden_b.png"), std::string::npos) << oneOnly;
  EXPECT_EQ(oneOnly.find("view_a.png"), std::string::npos) << oneOnly;

  const std::string identical = test::errorMessage([&] { preparer.prepare(s.a, s.a, marker()); });
  EXPECT_NE(identical.find("identical"), std::string::npos) << identical;

  // Same place, different images (e.g. lighting changed): no baseline either.
  cv::Mat brighter = s.a.image + cv::Scalar(3);
  const std::string samePlace = test::errorMessage([&] {
    preparer.prepare(s.a, {brighter, "brighter.png"}, s.T_A, s.T_A, "given");
  });
  EXPECT_NE(samePlace.find("mm apart"), std::string::npos) << samePlace;

  const ReferencePreparer halfCamera(s.scene.camera.scaled(0.5));
  const std::string size = test::errorMessage([&] { halfCamera.prepare(s.a, s.b, marker()); });
  EXPECT_NE(size.find("640x480"), std::string::npos) << size;
  EXPECT_NE(size.find("320x240"), std::string::npos) << size;

  const std::string empty = test::errorMessage([&] {
    preparer.prepare({cv::Mat(), "gone.png"}, s.b, marker());
  });
  EXPECT_NE(empty.find("gone.png"), std::string::npos) << empty;

  // Poses that disagree with the images: no match survives the epipolar gate.
  const RigidPose swapped =
      s.T_B * RigidPose::fromVector6((Vector6d() << 0.1, 0, 0, 0, 0.2, 0).finished());
  const std::string wrongPoses =
      test::errorMessage([&] { preparer.prepare(s.a, s.b, s.T_A, swapped, "bad"); });
  EXPECT_NE(wrongPoses.find("matches survived"), std::string::npos) << wrongPoses;
}

TEST(ReferencePreparerParams, CheckNamesTheFieldAndYamlRoundTrips) {
  ReferencePreparerParams p;
  p.minMatches = -1;
  EXPECT_NE(test::errorMessage([&] { p.check(); }).find("preparation.min_matches"),
            std::string::npos);
  p = {};
  p.corners.countAt320x240 = 1;
  EXPECT_NE(test::errorMessage([&] { p.check(); }).find("corners.count"), std::string::npos);

  ReferencePreparerParams q;
  q.matching.minScore = 0.65;
  q.marker.ambiguityRatio = 1.5;
  q.minBaselineMetres = 0.05;
  q.corners.countAt320x240 = 200;
  const auto dir = test::freshTempDir("ReferencePreparerParams_yaml");
  std::ofstream(dir / "params.yml") << q.toYaml();
  const ReferencePreparerParams r = ReferencePreparerParams::load(dir / "params.yml");
  EXPECT_DOUBLE_EQ(r.matching.minScore, 0.65);
  EXPECT_DOUBLE_EQ(r.marker.ambiguityRatio, 1.5);
  EXPECT_DOUBLE_EQ(r.minBaselineMetres, 0.05);
  EXPECT_EQ(r.corners.countAt320x240, 200);

  {
    std::ofstream f(dir / "bad.yml");
    f << "%YAML:1.0\n---\nmatching:\n  min_depth_m: -3\n";
  }
  const std::string bad =
      test::errorMessage([&] { ReferencePreparerParams::load(dir / "bad.yml"); });
  EXPECT_NE(bad.find("bad.yml"), std::string::npos) << bad;
  EXPECT_NE(bad.find("matching.min_depth_m"), std::string::npos) << bad;
}

TEST(ReferencePreparerParams, UnknownKeysNameTheNearestAndTheYamlLineIsOptional) {
  const auto dir = test::freshTempDir("ReferencePreparerParams_strict");
  const auto load = [&](const std::string& body) {
    std::ofstream(dir / "p.yml") << body;
    return test::errorMessage([&] { ReferencePreparerParams::load(dir / "p.yml"); });
  };
  EXPECT_NE(load("preparation:\n  min_baseline: 0.1\n")
                .find("preparation.min_baseline: unknown key — did you mean "
                      "preparation.min_baseline_m?"),
            std::string::npos);
  EXPECT_NE(load("matchin:\n  min_score: 0.5\n")
                .find("matchin: unknown section — did you mean matching?"),
            std::string::npos);
  // The key the matcher reads but did not write before is known too.
  EXPECT_EQ(load("matching:\n  max_peak_offset_px: 2\n"), "(no error)");
  EXPECT_EQ(load("marker: {ambiguity_ratio: 1.7}\n"), "(no error)");
  // A caller that reads more sections from the same file names them.
  const cv::FileStorage extend("%YAML:1.0\nextension: {max_angle_deg: 10}\n",
                               cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ReferencePreparerParams p;
  EXPECT_NE(test::errorMessage([&] { p.read(extend.root()); }).find("extension: unknown section"),
            std::string::npos);
  EXPECT_EQ(test::errorMessage([&] { p.read(extend.root(), {"extension"}); }), "(no error)");
}
