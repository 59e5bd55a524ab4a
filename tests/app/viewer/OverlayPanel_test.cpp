// OverlayPanel: placed where asked; drawing leaves the settings alone; choosing the cube clears
// the model path; "Debug overlay" switches the tracker's layers together; with a tracked scene
// the object stands on it until "On the scene" is unticked.
#include "app/viewer/OverlayPanel.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(OverlayPanel, DrawingKeepsSettingsAndCubeChoiceClearsTheModel) {
  test::ImGuiTestContext ui;
  OverlaySettings settings;
  settings.modelPath = "house.obj";
  OverlayPanelEdit edit;
  const cv::Rect2f place(950, 0, 330, 300);
  auto draw = [&] { drawOverlayPanel(settings, edit, place); };
  ui.frame(draw);
  ImGuiWindow* w = test::ImGuiTestContext::window("Overlay");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.x, 950.0f);
  EXPECT_EQ(settings.modelPath, "house.obj");
  EXPECT_TRUE(edit.useModel);
  EXPECT_EQ(edit.modelPath, "house.obj");
  // The "Cube" radio button is the first widget: below the 19 px title bar and 8 px padding.
  ui.clickAt(950 + 14, 19 + 8 + 9, draw);
  EXPECT_FALSE(edit.useModel);
  EXPECT_TRUE(settings.modelPath.empty());
  EXPECT_DOUBLE_EQ(settings.size, OverlaySettings{}.size);
}

// Widget rows are 23 px apart (19 px frame + 4 px spacing) below the 19 px title bar and 8 px
// padding; x = 14 is inside the first widget of a row. Row y centre:
static float rowY(int row) { return 19 + 8 + 23.0f * row + 9; }

// "Debug overlay" (row 7 without a scene: cube/model, size, 3 offsets, line, dots+epipolar)
// turns the corners, matches and labels on and off together.
TEST(OverlayPanel, DebugOverlaySwitchesCornersMatchesAndLabels) {
  test::ImGuiTestContext ui;
  OverlaySettings settings;
  OverlayPanelEdit edit;
  auto draw = [&] { drawOverlayPanel(settings, edit, {950, 0, 330, 300}); };
  ui.frame(draw);
  EXPECT_FALSE(settings.showCorners || settings.showMatches || settings.showLabels);
  ui.clickAt(950 + 14, rowY(7), draw);
  EXPECT_TRUE(settings.showCorners && settings.showMatches && settings.showLabels);
  EXPECT_FALSE(settings.showEpipolarLines);
  ui.clickAt(950 + 14, rowY(7), draw);
  EXPECT_FALSE(settings.showCorners || settings.showMatches || settings.showLabels);
}

// With a tracked scene the object stands on it (the panel applies the placement); unticking
// "On the scene" (row 1) leaves it at the same base, upright in the world frame.
TEST(OverlayPanel, SceneCheckboxPlacesTheObjectOnTheScene) {
  test::ImGuiTestContext ui;
  OverlaySettings settings;
  OverlayPanelEdit edit;
  ScenePlacement scene;
  scene.base = Eigen::Vector3d(0.1, -0.1, 0.02);
  scene.rotation = Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()).toRotationMatrix();
  scene.edge = 0.05;
  edit.scene = scene;
  auto draw = [&] { drawOverlayPanel(settings, edit, {950, 0, 330, 300}); };
  ui.frame(draw);
  EXPECT_TRUE(settings.offset.isApprox(scene.base));
  EXPECT_TRUE(settings.orientation.isApprox(scene.rotation));
  EXPECT_DOUBLE_EQ(settings.size, 0.05);
  ui.clickAt(950 + 14, rowY(1), draw);
  EXPECT_FALSE(settings.onScene);
  EXPECT_TRUE(settings.sizeFromScene);
  EXPECT_TRUE(settings.offset.isApprox(scene.base));
  EXPECT_TRUE(settings.orientation.isIdentity());
}
