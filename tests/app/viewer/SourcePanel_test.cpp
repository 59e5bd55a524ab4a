// SourcePanel: placed where asked; Pause and Step buttons set the play state and step request.
#include "app/viewer/SourcePanel.hpp"

#include <gtest/gtest.h>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(SourcePanel, ButtonsDriveThePlayState) {
  test::ImGuiTestContext ui;
  SourceState state;
  state.description = "scripted";
  state.frameCount = 100;
  state.seekable = true;
  state.currentIndex = 7;
  const cv::Rect2f place(0, 0, 330, 170);
  auto draw = [&] { drawSourcePanel(state, place); };
  ui.frame(draw);
  ImGuiWindow* w = test::ImGuiTestContext::window("Source");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.x, 0.0f);
  EXPECT_EQ(w->Size.x, 330.0f);
  // Default ImGui 1.86 style with the built-in 13 px font: title bar 19 px, window padding 8,
  // two text lines of 17 px, then the button row (frame padding 3): y in [61, 80]. "Pause" is
  // 5 glyphs of 7 px plus 2 x 4 px padding, from x = 8; "Step" follows after 8 px spacing.
  EXPECT_TRUE(state.playing);
  ui.clickAt(25, 70, draw);
  EXPECT_FALSE(state.playing) << "Pause not clicked";
  EXPECT_FALSE(state.stepRequested);
  ui.clickAt(72, 70, draw);
  EXPECT_TRUE(state.stepRequested) << "Step not clicked";
  ui.clickAt(25, 70, draw);  // now labelled "Play"
  EXPECT_TRUE(state.playing);
  EXPECT_FALSE(state.seekRequest);  // untouched slider: no seek
}
