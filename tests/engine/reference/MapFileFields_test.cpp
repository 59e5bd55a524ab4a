#include "engine/reference/MapFileFields.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <opencv2/imgcodecs.hpp>

#include "ErrorMessage.hpp"
#include "TestPaths.hpp"
#include "engine/config/ConfigFile.hpp"

using namespace reftrack;

namespace {

constexpr const char* kWhere = "reference map 'm/map.yml'";

// The YAML text `write` produces, read back as map.yml is.
template <class Write>
YamlNode writtenAndReadBack(Write&& write) {
  cv::FileStorage out(
      ".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  write(out);
  return readConfigText(out.releaseAndGetString(), kWhere);
}

YamlNode yaml(const std::string& text) { return readConfigText("%YAML:1.0\n" + text, kWhere); }

struct CheckedThing {
  bool good = true;
  void check() const {
    if (!good) throw Error("thing is bad");
  }
};

}  // namespace

TEST(MapFileFields, CameraPoseAndCornersRoundTripExactly) {
  const PinholeCamera camera(
      (Eigen::Matrix3d() << 150.0, 0, 79.5, 0, 151.0, 59.5, 0, 0, 1).finished(), {160, 120},
      {0.01, -0.002, 0.0005, 0.0001, 0.0});
  const RigidPose T =
      RigidPose::fromVector6((Vector6d() << 0.1, -0.2, 1, 0.3, -0.1, 0.2).finished());
  const std::vector<ReferenceCorner> corners = {{{10.5f, 20.25f}, 30.f}, {{100.f, 60.f}, 12.5f}};
  const YamlNode root = writtenAndReadBack([&](cv::FileStorage& out) {
    writeMapCamera(out, camera);
    out << "T" << poseToMat(T) << "corners" << cornersToMat(corners);
  });
  const MapFieldReader read(kWhere, "m");
  const PinholeCamera cameraBack = read.readCamera(root);
  EXPECT_EQ(cameraBack.K(), camera.K());  // YAML doubles are written with 17 digits: exact
  EXPECT_EQ(cameraBack.imageSize(), camera.imageSize());
  EXPECT_EQ(cameraBack.distortion(), camera.distortion());
  EXPECT_EQ(read.readPose(root, "T", "T").matrix4(), T.matrix4());
  const std::vector<ReferenceCorner> cornersBack = read.readCorners(root, "corners", "corners");
  ASSERT_EQ(cornersBack.size(), corners.size());
  for (std::size_t i = 0; i < corners.size(); ++i) {
    EXPECT_EQ(cornersBack[i].pixel, corners[i].pixel);
    EXPECT_EQ(cornersBack[i].rmsContrast, corners[i].rmsContrast);
  }
}

TEST(MapFileFields, ReaderNamesTheFileAndTheField) {
  const MapFieldReader read(kWhere, "m");
  const YamlNode root = yaml(
      "T: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n"
      "  data: [ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 ]\n"
      "scaled: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n"
      "  data: [ 2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 ]\n"
      "nan: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n"
      "  data: [ .Nan, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 ]\n"
      "flat: !!opencv-matrix\n  rows: 2\n  cols: 2\n  dt: d\n  data: [ 1, 0, 0, 1 ]\n"
      "short: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: d\n  data: [ 1, 0 ]\n"
      "count: many\n");
  EXPECT_EQ(read.readPose(root, "T", "views[0].T").matrix4(), Eigen::Matrix4d::Identity());
  EXPECT_EQ(test::errorMessage([&] { read.readPose(root, "missing", "views[1].T"); }),
            std::string(kWhere) + ": missing field 'views[1].T' (truncated file?)");
  EXPECT_EQ(test::errorMessage([&] { read.readPose(root, "scaled", "T_A"); }),
            std::string(kWhere) + ": field 'T_A' is not a rigid transform");
  EXPECT_EQ(test::errorMessage([&] { read.readPose(root, "nan", "T_B"); }),
            std::string(kWhere) + ": field 'T_B' is not finite");
  EXPECT_EQ(test::errorMessage([&] { read.readPose(root, "flat", "T"); }),
            std::string(kWhere) + ": field 'T' has the wrong shape (2x2)");
  EXPECT_EQ(test::errorMessage([&] { read.readCorners(root, "flat", "corners_a"); }),
            std::string(kWhere) + ": field 'corners_a' has the wrong shape (2x2)");
  EXPECT_EQ(test::errorMessage([&] { read.readPose(root, "short", "views[2].T"); }),
            std::string(kWhere) +
                ": line 26: short is not a valid matrix: its header asks for 16 values but 'data' "
                "holds 2");
  EXPECT_EQ(test::errorMessage([&] { read.readInt(root, "count", "point_count"); }),
            std::string(kWhere) + ": line 27: field 'point_count' must be an integer");
  EXPECT_EQ(test::errorMessage([&] { read.readText(root, "T", "format"); }),
            std::string(kWhere) + ": line 2: field 'format' must be text");
  EXPECT_EQ(test::errorMessage([&] {
              read.requireKnown(root, {"T", "scaled", "nan", "short", "count"});
            }),
            std::string(kWhere) + ": line 17: flat: unknown key — did you mean nan?");
}

TEST(MapFileFields, ReadsImagesBesideTheMapAndNamesTheMissingOne) {
  const auto dir = test::freshTempDir("MapFileFields_Images");
  cv::Mat image(12, 16, CV_8UC3);
  cv::randu(image, 0, 255);
  ASSERT_TRUE(cv::imwrite((dir / "a.png").string(), image));
  const MapFieldReader read(kWhere, dir);
  EXPECT_EQ(cv::norm(read.readImage("a.png", "reference_a"), image, cv::NORM_INF), 0.0);
  EXPECT_EQ(test::errorMessage([&] { read.readImage("b.png", "views[1].name"); }),
            std::string(kWhere) + ": reference image '" + (dir / "b.png").string() +
                "' (views[1].name) is missing");
  // A name the file system refuses (longer than NAME_MAX) is missing too, not a
  // std::filesystem_error: the fuzzer found it in a mangled map.yml.
  const std::string tooLong(300, 'r');
  EXPECT_EQ(test::errorMessage([&] { read.readImage(tooLong, "reference_a"); }),
            std::string(kWhere) + ": reference image '" + (dir / tooLong).string() +
                "' (reference_a) is missing (File name too long)");
}

TEST(MapFileFields, CheckCornersNamesTheCorner) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_NO_THROW(checkCorners({{{-0.5f, 119.5f}, 1.f}}, "cornersA", {160, 120}));
  EXPECT_EQ(test::errorMessage([&] {
              checkCorners({{{1.f, 1.f}, 1.f}, {{1.f, 1.f}, nan}}, "cornersA", {160, 120});
            }),
            "cornersA[1] is not finite");
  EXPECT_EQ(test::errorMessage([&] {
              checkCorners({{{159.6f, 1.f}, 1.f}}, "views[2].corners", {160, 120});
            }),
            "views[2].corners[0] lies outside the image");
}

TEST(MapFileFields, ReadCheckedMapNamesTheFileOnCheckErrors) {
  EXPECT_TRUE(readCheckedMap<CheckedThing>(kWhere, [](CheckedThing&) {}).good);
  EXPECT_EQ(test::errorMessage([&] {
              readCheckedMap<CheckedThing>(kWhere, [](CheckedThing& t) { t.good = false; });
            }),
            std::string(kWhere) + ": thing is bad");
}
