// OverlayPanel: placed where asked; drawing leaves the settings alone; choosing the cube clears
// the model path.
#include "app/viewer/OverlayPanel.hpp"

#include <gtest/gtest.h>

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
