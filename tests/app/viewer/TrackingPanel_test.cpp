// TrackingPanel: shows the tracker, and its Save button writes the parameter file.
#include "app/viewer/TrackingPanel.hpp"

#include <gtest/gtest.h>

#include "ImGuiTestSupport.hpp"
#include "TestPaths.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(TrackingPanel, SaveWritesTheParameterFile) {
  const auto dir = test::freshTempDir("TrackingPanel_Save");
  test::ImGuiTestContext ui;
  ViewerState state;
  state.trackerName = "scripted";
  state.paramsPath = (dir / "p.yml").string();
  state.settings.tracker.ransac.maxIterations = 42;
  // A tall panel so every control fits without scrolling.
  const cv::Rect2f place(0, 0, 330, 715);
  auto draw = [&] { drawTrackingPanel(state, place); };
  ui.frame(draw);
  ASSERT_NE(test::ImGuiTestContext::window("Tracking"), nullptr);
  EXPECT_FALSE(state.trackerParamsChanged);  // drawing alone changes nothing
  // Save is the first button of the last row (no message yet): the row ends at the window's
  // maximum cursor extent and is one frame (19 px) high.
  const float rowBottom = test::ImGuiTestContext::window("Tracking")->DC.CursorMaxPos.y;
  ui.clickAt(25, rowBottom - 9, draw);
  const bool saved = std::filesystem::exists(dir / "p.yml");
  ASSERT_TRUE(saved) << state.paramsMessage;
  EXPECT_EQ(TrackerParams::load(dir / "p.yml").ransac.maxIterations, 42);
  EXPECT_NE(state.paramsMessage.find("saved"), std::string::npos);
}
