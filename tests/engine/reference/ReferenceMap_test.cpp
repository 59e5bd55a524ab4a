#include "engine/reference/ReferenceMap.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;

namespace {

ReferenceMap makeMap() {
  ReferenceMap m;
  m.camera = PinholeCamera::fromFieldOfView({160, 120}, 60.0);
  m.T_A = RigidPose::fromVector6((Vector6d() << 0, 0, 1, 0.1, 0, 0).finished());
  m.T_B = RigidPose::fromVector6((Vector6d() << -0.2, 0, 1, 0.1, -0.2, 0).finished());
  m.imageA = cv::Mat(120, 160, CV_8UC3);
  m.imageB = cv::Mat(120, 160, CV_8UC3);
  cv::randu(m.imageA, 0, 255);
  cv::randu(m.imageB, 0, 255);
  m.cornersA = {{{10.5f, 20.25f}, 30.f}, {{100.f, 60.f}, 12.5f}};
  m.cornersB = {{{12.f, 21.f}, 28.f}};
  m.matches = {{0, 0, Eigen::Vector3d(0.1, -0.05, 1.2)}};
  m.poseSource = "test";
  return m;
}

std::string loadError(const std::filesystem::path& dir) {
  return test::errorMessage([&] { ReferenceMap::load(dir); });
}

// A copy of the map saved in dir/ok as dir/name with `text` as its map.yml (and its images, or
// none).
std::filesystem::path writeMapVariant(const std::filesystem::path& dir, const std::string& name,
                                      const std::string& text, bool withImages) {
  std::filesystem::create_directories(dir / name);
  std::ofstream(dir / name / "map.yml") << text;
  if (withImages)
    for (const char* image : {"reference_a.png", "reference_b.png"})
      std::filesystem::copy_file(dir / "ok" / image, dir / name / image);
  return dir / name;
}

}  // namespace

TEST(ReferenceMap, RoundTripsEveryField) {
  const auto dir = test::freshTempDir("ReferenceMap_RoundTrip");
  const ReferenceMap m = makeMap();
  m.save(dir / "scene");
  const ReferenceMap back = ReferenceMap::load(dir / "scene");
  EXPECT_LT((back.T_A.matrix4() - m.T_A.matrix4()).norm(), 1e-12);
  EXPECT_LT((back.T_B.matrix4() - m.T_B.matrix4()).norm(), 1e-12);
  EXPECT_LT((back.camera.K() - m.camera.K()).norm(), 1e-12);
  ASSERT_EQ(back.cornersA.size(), 2u);
  EXPECT_FLOAT_EQ(back.cornersA[0].pixel.y, 20.25f);
  EXPECT_FLOAT_EQ(back.cornersA[1].rmsContrast, 12.5f);
  ASSERT_EQ(back.matches.size(), 1u);
  EXPECT_LT((back.matches[0].pointA - m.matches[0].pointA).norm(), 1e-12);
  EXPECT_EQ(cv::norm(back.imageA, m.imageA, cv::NORM_INF), 0.0);
}

TEST(ReferenceMap, RefusesBrokenMapsWithTheirOwnMessages) {
  const auto dir = test::freshTempDir("ReferenceMap_Broken");
  makeMap().save(dir / "ok");
  const std::string yml = test::readTextFile(dir / "ok" / "map.yml");
  const auto variant = [&](const std::string& name, const std::string& text,
                           bool withImages = true) {
    return writeMapVariant(dir, name, text, withImages);
  };
  EXPECT_NE(loadError(dir / "absent").find("does not exist"), std::string::npos);
  EXPECT_NE(loadError(variant("truncated", yml.substr(0, yml.size() / 2))).find("truncated"),
            std::string::npos);
  std::string v2 = yml;
  v2.replace(v2.find("version: 1"), 10, "version: 7");
  EXPECT_NE(loadError(variant("version", v2)).find("format version 7"), std::string::npos);
  EXPECT_NE(loadError(variant("noimages", yml, false)).find("is missing"), std::string::npos);
  const auto small = variant("small", yml);
  cv::imwrite((small / "reference_b.png").string(), cv::Mat(60, 80, CV_8UC3, cv::Scalar(0)));
  EXPECT_NE(loadError(small).find("but the camera is 160x120"), std::string::npos);
}

TEST(ReferenceMap, RefusesIdenticalReferencePoses) {
  ReferenceMap m = makeMap();
  m.T_B = m.T_A;
  EXPECT_THROW(m.check(), Error);
}

TEST(ReferenceMap, LoadNamesUnknownKeysAndNeedsNoYamlLine) {
  const auto dir = test::freshTempDir("ReferenceMap_Strict");
  makeMap().save(dir / "ok");
  const std::string yml = test::readTextFile(dir / "ok" / "map.yml");
  const auto variant = [&](const std::string& name, const std::string& text) {
    return writeMapVariant(dir, name, text, true);
  };
  std::string misspelt = yml;
  misspelt.replace(misspelt.find("pose_source:"), 12, "pose_sourse:");
  EXPECT_NE(loadError(variant("key", misspelt))
                .find("map.yml': line " +
                      std::to_string(1 + std::count(yml.begin(),
                                                    yml.begin() + yml.find("pose_source:"), '\n')) +
                      ": pose_sourse: unknown key — did you mean pose_source?"),
            std::string::npos);
  ASSERT_EQ(yml.rfind("%YAML:1.0\n", 0), 0u);
  EXPECT_EQ(loadError(variant("bare", yml.substr(10))), "(no error)");
}
