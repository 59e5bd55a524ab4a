#include "engine/reference/MultiReferenceMap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

cv::Mat randomImage() {
  cv::Mat img(120, 160, CV_8UC3);
  cv::randu(img, 0, 255);
  return img;
}

// Three references looking at points about 1.2 m in front of the first; every point is in front
// of every camera.
MultiReferenceMap makeMap() {
  MultiReferenceMap m;
  m.camera =
      PinholeCamera((Eigen::Matrix3d() << 150.0, 0, 79.5, 0, 151.0, 59.5, 0, 0, 1).finished(),
                    {160, 120}, {0.01, -0.002, 0.0005, 0.0001, 0.0});
  const Vector6d poses[3] = {(Vector6d() << 0, 0, 1, 0.1, 0, 0).finished(),
                             (Vector6d() << -0.2, 0, 1, 0.1, -0.2, 0).finished(),
                             (Vector6d() << 0.1, 0.3, 1.1, 0.2, 0.1, 0.05).finished()};
  for (int v = 0; v < 3; ++v) {
    ReferenceView view;
    view.name = "reference_0" + std::to_string(v) + ".png";
    view.T = RigidPose::fromVector6(poses[v]);
    view.anchored = v != 2;
    view.image = randomImage();
    view.corners = {{{10.5f + v, 20.25f}, 30.f}, {{100.f, 60.f + v}, 12.5f}, {{50.f, 50.f}, 7.f}};
    m.views.push_back(view);
  }
  ReferenceKeypoints& kp = m.views[1].keypoints;
  kp.keypoints = {cv::KeyPoint(12.5f, 30.25f, 31.f, 45.5f, 0.003f, 2),
                  cv::KeyPoint(70.f, 40.f, 15.f, 270.f, 0.01f, 0)};
  kp.descriptors = cv::Mat(2, 32, CV_8U);
  cv::randu(kp.descriptors, 0, 255);
  kp.points = {Eigen::Vector3d(0.01, 0.02, 0.03),
               Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN())};
  // Two observations measured at a correlation peak next to their corner, the others at the
  // corner itself (no peak).
  m.points = {
      {Eigen::Vector3d(0.1, -0.05, 0.2), {{0, 0}, {1, 0, cv::Point2f(12.25f, 19.5f)}, {2, 1}}},
      {Eigen::Vector3d(-0.05, 0.02, 0.1), {{1, 2}, {2, 0, cv::Point2f(13.125f, 21.f)}}},
      {Eigen::Vector3d(0.0, 0.0, 0.0), {{0, 2}, {2, 2}}}};
  m.keypointKind = "orb";
  m.poseSource = "test";
  m.preparationParams = "corners: 3\n";
  return m;
}

std::string checkError(const MultiReferenceMap& m) {
  return test::errorMessage([&] { m.check(); });
}

std::string loadError(const std::filesystem::path& dir) {
  return test::errorMessage([&] { MultiReferenceMap::load(dir); });
}

// A copy of the map saved in dir/ok as dir/name with `text` as its map.yml.
std::filesystem::path writeMapVariant(const std::filesystem::path& dir,
                                      const MultiReferenceMap& good, const std::string& name,
                                      const std::string& text) {
  std::filesystem::create_directories(dir / name);
  std::ofstream(dir / name / "map.yml") << text;
  for (const ReferenceView& v : good.views)
    std::filesystem::copy_file(dir / "ok" / v.name, dir / name / v.name);
  return dir / name;
}

}  // namespace

TEST(MultiReferenceMap, RoundTripsEveryFieldExactly) {
  const auto dir = test::freshTempDir("MultiReferenceMap_RoundTrip");
  const MultiReferenceMap m = makeMap();
  m.save(dir / "scene");
  const MultiReferenceMap back = MultiReferenceMap::load(dir / "scene");
  EXPECT_EQ(back.camera.K(), m.camera.K());
  EXPECT_EQ(back.camera.distortion(), m.camera.distortion());
  EXPECT_EQ(back.camera.imageSize(), m.camera.imageSize());
  EXPECT_EQ(back.keypointKind, "orb");
  EXPECT_EQ(back.poseSource, "test");
  EXPECT_EQ(back.preparationParams, m.preparationParams);
  ASSERT_EQ(back.size(), 3);
  for (int v = 0; v < 3; ++v) {
    const ReferenceView &a = m.views[v], &b = back.views[v];
    EXPECT_EQ(b.name, a.name);
    // FileStorage writes doubles with 16 significant digits: round trip within 1 ulp-ish.
    EXPECT_LT((b.T.matrix4() - a.T.matrix4()).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_EQ(b.anchored, a.anchored);
    EXPECT_EQ(cv::norm(b.image, a.image, cv::NORM_INF), 0.0);
    ASSERT_EQ(b.corners.size(), a.corners.size());
    for (std::size_t i = 0; i < a.corners.size(); ++i) {
      EXPECT_EQ(b.corners[i].pixel, a.corners[i].pixel);
      EXPECT_EQ(b.corners[i].rmsContrast, a.corners[i].rmsContrast);
    }
  }
  const ReferenceKeypoints& kp = back.views[1].keypoints;
  ASSERT_EQ(kp.keypoints.size(), 2u);
  EXPECT_EQ(kp.keypoints[0].pt, cv::Point2f(12.5f, 30.25f));
  EXPECT_EQ(kp.keypoints[0].angle, 45.5f);
  EXPECT_EQ(kp.keypoints[0].octave, 2);
  EXPECT_EQ(cv::norm(kp.descriptors, m.views[1].keypoints.descriptors, cv::NORM_INF), 0.0);
  EXPECT_EQ(kp.points[0], m.views[1].keypoints.points[0]);
  EXPECT_TRUE(std::isnan(kp.points[1].x()) && std::isnan(kp.points[1].z()))
      << "a keypoint without a 3D point keeps NaN through YAML";
  EXPECT_EQ(kp.pointCount(), 1);
  EXPECT_TRUE(back.views[0].keypoints.empty());
  ASSERT_EQ(back.points.size(), m.points.size());
  for (std::size_t p = 0; p < m.points.size(); ++p) {
    EXPECT_LT((back.points[p].world - m.points[p].world).cwiseAbs().maxCoeff(), 1e-15);
    ASSERT_EQ(back.points[p].observations.size(), m.points[p].observations.size());
    for (std::size_t o = 0; o < m.points[p].observations.size(); ++o) {
      const PointObservation &a = m.points[p].observations[o], &b = back.points[p].observations[o];
      EXPECT_EQ(b.view, a.view);
      EXPECT_EQ(b.corner, a.corner);
      // Format 3 stores every observation's measured pixel: the peak where there is one, the
      // corner otherwise (floats, exactly).
      ASSERT_TRUE(b.peak.has_value());
      EXPECT_EQ(*b.peak, m.measuredPixel(a));
      if (a.peak) {
        EXPECT_EQ(*b.peak, *a.peak);
      }
    }
  }
  EXPECT_EQ(*back.points[0].observations[1].peak, cv::Point2f(12.25f, 19.5f));
  EXPECT_EQ(*back.points[0].observations[0].peak, m.views[0].corners[0].pixel);
}

// A map made from denser corners keeps their parameters (the tracker detects its frames so);
// one without keeps none, and a bad value in the section is named.
TEST(MultiReferenceMap, KeepsTheDenserCornersItWasMadeFrom) {
  const auto dir = test::freshTempDir("MultiReferenceMap_DenserCorners");
  MultiReferenceMap m = makeMap();
  m.save(dir / "plain");
  EXPECT_FALSE(MultiReferenceMap::load(dir / "plain").denserCorners.has_value());
  EXPECT_EQ(test::readTextFile(dir / "plain" / "map.yml").find("denser_corners"),
            std::string::npos);
  CornerParams denser;
  denser.countAt320x240 = 1000;
  denser.quality = 1e-6;
  denser.minDistancePx = 2.0;
  m.denserCorners = denser;
  m.save(dir / "ok");
  const MultiReferenceMap back = MultiReferenceMap::load(dir / "ok");
  ASSERT_TRUE(back.denserCorners.has_value());
  EXPECT_EQ(back.denserCorners->countAt320x240, 1000);
  EXPECT_EQ(back.denserCorners->quality, 1e-6);
  EXPECT_EQ(back.denserCorners->minDistancePx, 2.0);
  // The pairs the tracker runs on carry it, and a pair's map gives it back.
  ASSERT_TRUE(back.pair(0, 1).denserCorners.has_value());
  EXPECT_EQ(back.pair(0, 1).denserCorners->countAt320x240, 1000);
  EXPECT_EQ(MultiReferenceMap::fromPair(back.pair(0, 1)).denserCorners->quality, 1e-6);

  std::string yml = test::readTextFile(dir / "ok" / "map.yml");
  const std::size_t count = yml.find("count: 1000", yml.find("\ndenser_corners:"));
  ASSERT_NE(count, std::string::npos);
  yml.replace(count, 11, "count: -3");
  const std::string error = loadError(writeMapVariant(dir, m, "bad", yml));
  EXPECT_NE(error.find("field 'denser_corners'"), std::string::npos) << error;
  EXPECT_NE(error.find("corners.count"), std::string::npos) << error;
  // Set in memory, the map's check names it too (and a pair's, which the tracker checks).
  m.denserCorners->quality = std::nan("");
  EXPECT_NE(checkError(m).find("denser_corners: parameter 'corners.quality'"), std::string::npos)
      << checkError(m);
  EXPECT_NE(test::errorMessage([&] { m.pair(0, 1).check(); }).find("denser corners: "),
            std::string::npos);
}

TEST(MultiReferenceMap, LoadsAVersionTwoMapAtItsCorners) {
  // Format 2 is format 3 without observation_peaks: every observation is measured at its corner.
  const auto dir = test::freshTempDir("MultiReferenceMap_V2");
  const MultiReferenceMap good = makeMap();
  good.save(dir / "ok");
  std::string v2 = test::readTextFile(dir / "ok" / "map.yml");
  const std::size_t version = v2.find("version: 3\n");
  ASSERT_NE(version, std::string::npos);
  v2.replace(version, 10, "version: 2");
  const std::size_t peaks = v2.find("observation_peaks:"), after = v2.find("preparation_params:");
  ASSERT_NE(peaks, std::string::npos);
  ASSERT_NE(after, std::string::npos);
  const std::string withPeaks = v2;
  v2.erase(peaks, after - peaks);
  const std::filesystem::path v2Map = writeMapVariant(dir, good, "v2", v2);
  const MultiReferenceMap m = MultiReferenceMap::load(v2Map);
  ASSERT_EQ(m.points.size(), good.points.size());
  for (std::size_t p = 0; p < m.points.size(); ++p)
    for (const PointObservation& o : m.points[p].observations) {
      EXPECT_FALSE(o.peak.has_value());
      EXPECT_EQ(m.measuredPixel(o), good.views[static_cast<std::size_t>(o.view)]
                                        .corners[static_cast<std::size_t>(o.corner)]
                                        .pixel);
    }
  // A version-2 file with the version-3 field is not a version-2 map.
  EXPECT_NE(loadError(writeMapVariant(dir, good, "v2peaks", withPeaks))
                .find("observation_peaks: unknown key"),
            std::string::npos);
  // Saved again, it is a version-3 map with the corners as peaks.
  m.save(dir / "v3");
  EXPECT_NE(test::readTextFile(dir / "v3" / "map.yml").find("version: 3\n"), std::string::npos);
  const MultiReferenceMap back = MultiReferenceMap::load(dir / "v3");
  EXPECT_EQ(*back.points[0].observations[1].peak, good.views[1].corners[0].pixel);
}

TEST(MultiReferenceMap, PeaksTravelThroughPairAndFromPair) {
  const MultiReferenceMap m = makeMap();
  // Point 0 is seen by views 0 (corner 0, no peak) and 1 (corner 0, peak).
  const ReferenceMap p = m.pair(0, 1);
  ASSERT_EQ(p.matches.size(), 1u);
  EXPECT_FALSE(p.matches[0].peakA.has_value());
  ASSERT_TRUE(p.matches[0].peakB.has_value());
  EXPECT_EQ(*p.matches[0].peakB, cv::Point2f(12.25f, 19.5f));
  const MultiReferenceMap back = MultiReferenceMap::fromPair(p);
  ASSERT_EQ(back.points.size(), 1u);
  EXPECT_FALSE(back.points[0].observations[0].peak.has_value());
  EXPECT_EQ(back.points[0].observations[1].peak, p.matches[0].peakB);
}

TEST(MultiReferenceMap, LoadsAVersionOneMap) {
  const auto dir = test::freshTempDir("MultiReferenceMap_V1");
  ReferenceMap v1;
  v1.camera = PinholeCamera::fromFieldOfView({160, 120}, 60.0);
  v1.T_A = RigidPose::fromVector6((Vector6d() << 0, 0, 1, 0.1, 0, 0).finished());
  v1.T_B = RigidPose::fromVector6((Vector6d() << -0.2, 0, 1, 0.1, -0.2, 0).finished());
  v1.imageA = randomImage();
  v1.imageB = randomImage();
  v1.cornersA = {{{10.5f, 20.25f}, 30.f}, {{100.f, 60.f}, 12.5f}};
  v1.cornersB = {{{12.f, 21.f}, 28.f}, {{90.f, 61.f}, 11.f}};
  v1.matches = {{1, 0, Eigen::Vector3d(0.1, -0.05, 1.2)}, {0, 1, Eigen::Vector3d(0, 0.1, 0.9)}};
  v1.poseSource = "marker DICT_6X6_250:23:0.2";
  v1.save(dir / "v1");
  const MultiReferenceMap m = MultiReferenceMap::load(dir / "v1");
  ASSERT_EQ(m.size(), 2);
  EXPECT_EQ(m.poseSource, v1.poseSource);
  EXPECT_EQ(m.views[0].name, "reference_a.png");
  EXPECT_EQ(cv::norm(m.views[1].image, v1.imageB, cv::NORM_INF), 0.0);
  ASSERT_EQ(m.points.size(), 2u);
  // pair(0, 1) gives the version-1 map back: same corners, matches and camera-A points.
  const ReferenceMap pair = m.pair(0, 1);
  ASSERT_EQ(pair.matches.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(pair.matches[i].cornerA, v1.matches[i].cornerA);
    EXPECT_EQ(pair.matches[i].cornerB, v1.matches[i].cornerB);
    // world = T_A^-1 * pointA and back: a few ulps of metres.
    EXPECT_LT((pair.matches[i].pointA - v1.matches[i].pointA).norm(), 1e-12);
  }
  EXPECT_LT((pair.T_B.matrix4() - v1.T_B.matrix4()).norm(), 1e-12);
}

TEST(MultiReferenceMap, PairHoldsThePointsBothViewsSee) {
  const MultiReferenceMap m = makeMap();
  EXPECT_EQ(m.sharedPoints(0, 2), 2);
  EXPECT_EQ(m.sharedPoints(0, 1), 1);
  const ReferenceMap p = m.pair(2, 0);
  ASSERT_EQ(p.matches.size(), 2u);
  EXPECT_EQ(p.cornersA.size(), m.views[2].corners.size());
  for (const ReferenceMatch& match : p.matches) {
    // The pair's point, back in the world, is the map point observed by those two corners.
    const Eigen::Vector3d world = m.views[2].T.inverse() * match.pointA;
    bool found = false;
    for (const MapPoint& point : m.points) {
      int ca = -1, cb = -1;
      for (const PointObservation& o : point.observations) {
        if (o.view == 2) ca = o.corner;
        if (o.view == 0) cb = o.corner;
      }
      if (ca == match.cornerA && cb == match.cornerB) {
        found = true;
        EXPECT_LT((point.world - world).norm(), 1e-12);
      }
    }
    EXPECT_TRUE(found);
  }
  EXPECT_THROW(m.pair(1, 1), Error);
  EXPECT_THROW(m.pair(0, 3), Error);
}

TEST(MultiReferenceMap, CheckNamesTheBadField) {
  EXPECT_EQ(checkError(makeMap()), "(no error)");
  const auto broken = [](auto edit) {
    MultiReferenceMap m = makeMap();
    edit(m);
    return checkError(m);
  };
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[1].observations[0].view = 3;
            }).find("points[1].observations[0].view 3 is out of range"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[0].observations[2].corner = 3;
            }).find("points[0].observations[2].corner 3 is out of range"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[0].observations[1].view = 0;
            }).find("points[0].observations[1].view 0 appears twice"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[2].observations.pop_back();
            }).find("points[2].observations: 1 observation(s)"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[2].world.y() = std::numeric_limits<double>::quiet_NaN();
            }).find("points[2].world is not finite"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[2].world.z() = -5.0;
            }).find("points[2].world lies behind the camera of views[0]"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[1].observations[1].peak->y = std::numeric_limits<float>::infinity();
            }).find("points[1].observations[1].peak is not finite"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.points[0].observations[2].peak = cv::Point2f(-1.f, 5.f);
            }).find("points[0].observations[2].peak lies outside the image"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.views[1].corners[1].pixel.x = std::numeric_limits<float>::quiet_NaN();
            }).find("views[1].corners[1] is not finite"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.views[2].corners[0].pixel.x = 400.f;
            }).find("views[2].corners[0] lies outside the image"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.views[2].image = cv::Mat(60, 80, CV_8UC3);
            }).find("views[2].image is 80x60 but the camera is 160x120"),
            std::string::npos);
  EXPECT_NE(
      broken([](MultiReferenceMap& m) { m.views[2].name = "../x.png"; }).find("views[2].name"),
      std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.views[2].name = m.views[0].name;
            }).find("views[2].name 'reference_00.png' is used by another view"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.views[1].keypoints.points.pop_back();
            }).find("views[1].keypoints"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) {
              m.views[2].T = m.views[0].T;
            }).find("views[2].pose is the same as views[0].pose"),
            std::string::npos);
  EXPECT_NE(broken([](MultiReferenceMap& m) { m.views.resize(1); }).find("at least 2 references"),
            std::string::npos);
}

TEST(MultiReferenceMap, LoadRefusesCorruptedFilesNamingTheField) {
  const auto dir = test::freshTempDir("MultiReferenceMap_Broken");
  const MultiReferenceMap good = makeMap();
  good.save(dir / "ok");
  const std::string yml = test::readTextFile(dir / "ok" / "map.yml");
  const auto variant = [&](const std::string& name, const std::string& text) {
    return writeMapVariant(dir, good, name, text);
  };
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = yml;
    const std::size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  EXPECT_NE(loadError(dir / "absent").find("does not exist"), std::string::npos);
  EXPECT_NE(loadError(variant("truncated", yml.substr(0, yml.size() / 2))).find("truncated"),
            std::string::npos);
  EXPECT_NE(loadError(variant("version", replaced("version: 3", "version: 9")))
                .find("format version 9; this reftrack reads versions 1, 2 and 3 (written by a "
                      "newer reftrack?)"),
            std::string::npos);
  EXPECT_NE(loadError(variant("version0", replaced("version: 3", "version: 0")))
                .find("format version 0; this reftrack reads versions 1, 2 and 3"),
            std::string::npos);
  // observation_peaks: one (x, y) row per observation row (7 here), not one number.
  std::string flatPeaks = yml;
  const std::size_t peakShape =
      flatPeaks.find("rows: 7\n   cols: 2", flatPeaks.find("\nobservation_peaks:"));
  ASSERT_NE(peakShape, std::string::npos);
  flatPeaks.replace(peakShape, 18, "rows: 14\n   cols: 1");
  EXPECT_NE(loadError(variant("peaks", flatPeaks))
                .find("field 'observation_peaks' has the wrong shape (14x1)"),
            std::string::npos);
  EXPECT_NE(loadError(variant("pointcount", replaced("point_count: 3", "point_count: 4")))
                .find("field 'points' has the wrong shape"),
            std::string::npos);
  EXPECT_NE(loadError(variant("name",
                              replaced("name: \"reference_01.png\"", "name: \"reference_07.png\"")))
                .find("reference_07.png' (views[1].name) is missing"),
            std::string::npos);
  // The observations are rows (point, view, corner): make the last row name view 5.
  std::string badView = yml;
  const std::size_t lastRow = badView.find("2, 2, 2 ]", badView.find("\nobservations:"));
  ASSERT_NE(lastRow, std::string::npos);
  badView.replace(lastRow, 7, "2, 5, 2");
  EXPECT_NE(loadError(variant("obsview", badView))
                .find("points[2].observations[1].view 5 is out of range"),
            std::string::npos);
  // A NaN coordinate of the last point (its x: the third row starts at the 7th number, "0.").
  std::string nanPoint = yml;
  const std::size_t lastPoint = nanPoint.find("0., 0., 0. ]", nanPoint.find("\npoints:"));
  ASSERT_NE(lastPoint, std::string::npos);
  nanPoint.replace(lastPoint, 2, ".Nan");
  EXPECT_NE(loadError(variant("nanpoint", nanPoint)).find("points[2].world is not finite"),
            std::string::npos);
  // A view pose that is not a rigid transform (its first entry scaled).
  std::string badPose = yml;
  const std::size_t poseData = badPose.find("data: [ 1., 0., 0., 0.", badPose.find("      T:"));
  ASSERT_NE(poseData, std::string::npos);
  badPose.replace(poseData, 11, "data: [ 2.,");
  EXPECT_NE(loadError(variant("pose", badPose)).find("field 'views[0].T' is not a rigid transform"),
            std::string::npos);
  // Two references only: a map needs at least two (the third's block removed).
  std::string twoViews = yml;
  const std::size_t third = twoViews.find("   -\n      name: \"reference_02.png\"");
  const std::size_t after = twoViews.find("point_count:");
  ASSERT_NE(third, std::string::npos);
  twoViews.erase(third, after - third);
  EXPECT_NE(loadError(variant("twoviews", twoViews)).find("observations[2].view 2 is out of range"),
            std::string::npos);
}

TEST(MultiReferenceMap, LoadNamesUnknownKeysAndNeedsNoYamlLine) {
  const auto dir = test::freshTempDir("MultiReferenceMap_Strict");
  const MultiReferenceMap good = makeMap();
  good.save(dir / "ok");
  const std::string yml = test::readTextFile(dir / "ok" / "map.yml");
  const auto variant = [&](const std::string& name, const std::string& text) {
    return writeMapVariant(dir, good, name, text);
  };
  // The first `from` after `after` replaced ("" : from the start; the second view begins at its
  // name "reference_01.png").
  const auto replaced = [&](const std::string& after, const std::string& from,
                            const std::string& to) {
    std::string text = yml;
    const std::size_t at = text.find(from, text.find(after));
    EXPECT_NE(at, std::string::npos) << from;
    return at == std::string::npos ? text : text.replace(at, from.size(), to);
  };
  const auto expectError = [&](const std::filesystem::path& map, const std::string& expected) {
    const std::string message = loadError(map);
    EXPECT_NE(message.find(expected), std::string::npos) << message;
  };
  const auto lineOf = [&](const std::string& key) {
    return std::to_string(1 + std::count(yml.begin(), yml.begin() + yml.find(key), '\n'));
  };
  expectError(variant("top", replaced("", "point_count:", "points_count:")),
              "map.yml': line " + lineOf("point_count:") +
                  ": points_count: unknown key — did you mean point_count?");
  expectError(variant("view", replaced("reference_01.png", "anchored:", "anchord:")),
              "views[1].anchord: unknown key — did you mean views[1].anchored?");
  expectError(variant("section", replaced("reference_01.png", "keypoints:", "keypoint:")),
              "views[1].keypoint: unknown section — did you mean views[1].keypoints?");
  expectError(variant("inner", replaced("reference_01.png", "count:", "cnt:")),
              "views[1].keypoints.cnt: unknown key — did you mean views[1].keypoints.count?");
  ASSERT_EQ(yml.rfind("%YAML:1.0\n", 0), 0u);
  const auto bare = variant("bare", yml.substr(10));
  EXPECT_EQ(loadError(bare), "(no error)");
  EXPECT_EQ(MultiReferenceMap::load(bare).points.size(), good.points.size());
}
