// ReferencesPanel: the relocalisation figures fold in frame by frame; the panel draws every
// reference (without textures: placeholders) at the requested place.
#include "app/viewer/ReferencesPanel.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

TEST(ReferencesState, CountsAttemptsSuccessesAndTheirTimes) {
  ReferencesState s;
  EXPECT_TRUE(std::isnan(s.lastMs()));
  EXPECT_TRUE(std::isnan(s.medianMs()));
  ReferencesFrame f;
  f.referenceA = 2;
  f.referenceB = 3;
  s.addFrame(f);  // tracked, no relocalisation
  EXPECT_EQ(s.referenceA, 2);
  EXPECT_EQ(s.attempts, 0);
  for (const auto& [ms, ok] :
       {std::pair{30.0, false}, std::pair{10.0, false}, std::pair{20.0, true}}) {
    ReferencesFrame a;
    a.relocalisationAttempted = true;
    a.relocalisationSucceeded = ok;
    a.relocalisationMs = ms;
    a.relocalisationMessage = ok ? "verified" : "too few inliers";
    s.addFrame(a);
  }
  EXPECT_EQ(s.attempts, 3);
  EXPECT_EQ(s.successes, 1);
  EXPECT_DOUBLE_EQ(s.lastMs(), 20.0);
  EXPECT_DOUBLE_EQ(s.medianMs(), 20.0);
  EXPECT_EQ(s.lastMessage, "verified");
  EXPECT_EQ(s.referenceA, -1);  // the last frame had no pair in use
}

TEST(ReferencesPanel, DrawsEveryReferenceInRows) {
  test::ImGuiTestContext ui;
  ReferencesState s;
  s.active = true;
  s.thumbnailSize = {96, 72};
  const cv::Rect2f place(950, 300, 330, 250);
  s.names = {"reference_0.png", "reference_1.png"};
  ui.frame([&] { drawReferencesPanel(s, place); });
  ImGuiWindow* w = test::ImGuiTestContext::window("References");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.x, 950.0f);
  EXPECT_EQ(w->Pos.y, 300.0f);
  const float twoHigh = w->DC.CursorMaxPos.y;
  // Three per row fit in 330 px: a fourth and fifth reference add one row of thumbnails.
  s.names = {"r0", "r1", "r2", "r3", "r4"};
  s.referenceA = 3;
  s.referenceB = 4;
  ui.frame([&] { drawReferencesPanel(s, place); });
  EXPECT_GT(w->DC.CursorMaxPos.y, twoHigh + 72.0f);
  EXPECT_LT(w->DC.CursorMaxPos.y, twoHigh + 2 * 72.0f + 40.0f);
}
