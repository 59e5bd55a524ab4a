// RecordPanel: Start requests a recording; while recording the button becomes Stop.
#include "app/viewer/RecordPanel.hpp"

#include <gtest/gtest.h>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(RecordPanel, StartAndStopSetRequests) {
  test::ImGuiTestContext ui;
  RecordState state;
  const cv::Rect2f place(0, 600, 330, 120);
  auto draw = [&] { drawRecordPanel(state, place); };
  ui.frame(draw);
  ImGuiWindow* w = test::ImGuiTestContext::window("Record");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.y, 600.0f);
  // The Start button is the last row (no message yet): it ends at the window's maximum cursor
  // extent and is one frame (19 px) high; it spans x 8..51.
  const float rowBottom = w->DC.CursorMaxPos.y;
  ui.clickAt(25, rowBottom - 9, draw);
  EXPECT_TRUE(state.startRequested);
  state.startRequested = false;
  state.recording = true;
  ui.clickAt(25, rowBottom - 9, draw);
  EXPECT_TRUE(state.stopRequested);
  EXPECT_FALSE(state.startRequested);
}
