// StatsPanel: draws from any history (empty, with gaps) at the requested place; the true overlay
// error's plot only when the viewer has ground truth.
#include "app/viewer/StatsPanel.hpp"

#include <gtest/gtest.h>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(StatsPanel, DrawsEmptyAndGappyHistories) {
  test::ImGuiTestContext ui;
  StatsHistory history;
  const cv::Rect2f place(950, 300, 330, 420);
  ui.frame([&] { drawStatsPanel(history, place); });
  ImGuiWindow* w = test::ImGuiTestContext::window("Stats");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.y, 300.0f);
  const float emptyHeight = w->DC.CursorMaxPos.y;
  for (int k = 0; k < 10; ++k) {
    FrameStats s;
    s.index = k;
    s.stages = {{"detect", 1.0}, {"match", 2.0}};
    if (k % 3) s.pose = Vector6d::Constant(0.1 * k);
    history.add(s);
  }
  ui.frame([&] { drawStatsPanel(history, place); });
  // The per-stage lines and the frame line add rows above the plots.
  EXPECT_GT(w->DC.CursorMaxPos.y, emptyHeight + 3 * 13);
}

TEST(StatsPanel, PlotsTheTrueErrorBesideThePredictedOneWithGroundTruth) {
  test::ImGuiTestContext ui;
  StatsHistory history;
  for (int k = 0; k < 5; ++k) {
    FrameStats s;
    s.index = k;
    s.predictedErrorPx = 0.3;
    s.trueErrorPx = 0.2;
    history.add(s);
  }
  const cv::Rect2f place(950, 0, 330, 900);  // tall enough for every plot
  ui.frame([&] { drawStatsPanel(history, place); });
  ImGuiWindow* w = test::ImGuiTestContext::window("Stats");
  ASSERT_NE(w, nullptr);
  const float withoutTruth = w->DC.CursorMaxPos.y;
  history.setGroundTruthLoaded(true);
  ui.frame([&] { drawStatsPanel(history, place); });
  EXPECT_GT(w->DC.CursorMaxPos.y, withoutTruth + 30);  // one more 36 px plot
}
