// OverlaySettings: cube placement, YAML round trip, and named errors for bad values.
#include "app/viewer/OverlaySettings.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(OverlaySettings, CubeStandsOnTheOffset) {
  OverlaySettings s;
  s.size = 0.2;
  s.offset = Eigen::Vector3d(1, 2, 3);
  const Eigen::Matrix4d T = s.cubeModelToWorld();
  EXPECT_TRUE((T.topLeftCorner<3, 3>().isIdentity()));
  EXPECT_TRUE((T.topRightCorner<3, 1>().isApprox(Eigen::Vector3d(1, 2, 3.1))));
}

TEST(OverlaySettings, RoundTripsThroughYaml) {
  OverlaySettings s;
  s.size = 0.07;
  s.offset = Eigen::Vector3d(0.1, -0.2, 0.3);
  s.modelPath = "assets/models/house.obj";
  s.lineWidthPx = 2.5f;
  s.vertexDots = false;
  s.showEpipolarLines = true;
  s.showCorners = false;
  cv::FileStorage out(
      "x.yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  out << "overlay"
      << "{";
  s.write(out);
  out << "}";
  const std::string text = out.releaseAndGetString();
  cv::FileStorage in(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  OverlaySettings r;
  r.read(in["overlay"]);
  EXPECT_DOUBLE_EQ(r.size, 0.07);
  EXPECT_TRUE(r.offset.isApprox(s.offset));
  EXPECT_EQ(r.modelPath, s.modelPath);
  EXPECT_FLOAT_EQ(r.lineWidthPx, 2.5f);
  EXPECT_FALSE(r.vertexDots);
  EXPECT_TRUE(r.showEpipolarLines);
  EXPECT_FALSE(r.showCorners);
  EXPECT_TRUE(r.showMatches);
}

TEST(OverlaySettings, BadValuesAreNamed) {
  OverlaySettings s;
  s.size = 0.0;
  try {
    s.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("overlay.size"), std::string::npos) << e.what();
  }
  s = OverlaySettings{};
  s.offset.y() = std::nan("");
  try {
    s.check();
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("overlay.offset_y"), std::string::npos) << e.what();
  }
  cv::FileStorage in("%YAML:1.0\n---\noverlay: {size: -1}\n", cv::FileStorage::READ |
                                                                  cv::FileStorage::MEMORY |
                                                                  cv::FileStorage::FORMAT_YAML);
  EXPECT_THROW(OverlaySettings{}.read(in["overlay"]), Error);
}
