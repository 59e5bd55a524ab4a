// OverlaySettings: cube placement (by hand and on the scene), YAML round trip, and named errors
// for bad values.
#include "app/viewer/OverlaySettings.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "ErrorMessage.hpp"
#include "engine/config/ConfigFile.hpp"
#include "engine/core/Error.hpp"
#include "render/WireframeCube.hpp"

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

// The predicted overlay error's object is the drawn cube: the renderer's own vertices.
TEST(OverlaySettings, CubeWorldVerticesAreTheDrawnCubes) {
  OverlaySettings s;
  s.size = 0.2;
  s.offset = Eigen::Vector3d(0.16, -0.1, 0.0);
  render::WireframeCubeStyle style;
  style.edgeLength = s.size;
  style.modelToWorld = s.cubeModelToWorld();
  const auto drawn = render::WireframeCube::worldVertices(style);
  const std::vector<Eigen::Vector3d> vertices = s.cubeWorldVertices();
  ASSERT_EQ(vertices.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_LT((vertices[i] - drawn[i]).norm(), 1e-12) << i;
  EXPECT_NEAR(vertices[0].z(), 0.0, 1e-12);  // standing on the offset
  EXPECT_NEAR(vertices[7].z(), 0.2, 1e-12);
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
  s.showMatches = true;
  s.onScene = false;
  cv::FileStorage out(
      "x.yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  out << "overlay"
      << "{";
  s.write(out);
  out << "}";
  OverlaySettings r;
  r.read(readConfigText(out.releaseAndGetString(), "settings")["overlay"]);
  EXPECT_DOUBLE_EQ(r.size, 0.07);
  EXPECT_TRUE(r.offset.isApprox(s.offset));
  EXPECT_EQ(r.modelPath, s.modelPath);
  EXPECT_FLOAT_EQ(r.lineWidthPx, 2.5f);
  EXPECT_FALSE(r.vertexDots);
  EXPECT_TRUE(r.showEpipolarLines);
  EXPECT_FALSE(r.showCorners);
  EXPECT_TRUE(r.showMatches);
  EXPECT_FALSE(r.showLabels);
  EXPECT_FALSE(r.onScene);
  EXPECT_TRUE(r.sizeFromScene);
}

// Defaults: a clean picture (no debug layer), placed on the scene and scaled to it when there is
// one; the cube then stands on the scene's plane along its normal.
TEST(OverlaySettings, AppliesTheScenePlacementUnlessPlacedByHand) {
  OverlaySettings s;
  EXPECT_FALSE(s.showCorners || s.showMatches || s.showLabels || s.showEpipolarLines);
  s.applyScene(std::nullopt);  // no map: as set
  EXPECT_TRUE(s.offset.isZero());
  EXPECT_DOUBLE_EQ(s.size, 0.1);
  ScenePlacement scene;
  scene.base = Eigen::Vector3d(0.3, 0.2, 0.1);
  scene.rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  scene.edge = 0.2;
  s.applyScene(scene);
  EXPECT_TRUE(s.offset.isApprox(scene.base));
  EXPECT_DOUBLE_EQ(s.size, 0.2);
  const std::vector<Eigen::Vector3d> v = s.cubeWorldVertices();
  const Eigen::Vector3d up = scene.rotation.col(2);
  for (int i = 0; i < 8; ++i)  // bit 2: the top face, one edge above the base's plane
    EXPECT_NEAR(up.dot(v[i] - scene.base), (i & 4) ? 0.2 : 0.0, 1e-12) << i;
  Eigen::Vector3d bottom = Eigen::Vector3d::Zero();
  for (int i = 0; i < 4; ++i) bottom += v[i] / 4;
  EXPECT_LT((bottom - scene.base).norm(), 1e-12);  // the base centre is the bottom face's centre
  OverlaySettings byHand;
  byHand.onScene = byHand.sizeFromScene = false;
  byHand.offset = Eigen::Vector3d(1, 2, 3);
  byHand.size = 0.05;
  byHand.applyScene(scene);
  EXPECT_TRUE(byHand.offset.isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(byHand.orientation.isIdentity());
  EXPECT_DOUBLE_EQ(byHand.size, 0.05);
  byHand.setDebugLayers(true);
  EXPECT_TRUE(byHand.showCorners && byHand.showMatches && byHand.showLabels);
  EXPECT_FALSE(byHand.showEpipolarLines);
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
  const YamlNode in = readConfigText("%YAML:1.0\n---\noverlay: {size: -1}\n", "settings");
  EXPECT_EQ(test::errorMessage([&] { OverlaySettings{}.read(in["overlay"]); }),
            "line 3: parameter 'overlay.size' must lie in [0.000001, 1000.000000], got -1.000000");
}
