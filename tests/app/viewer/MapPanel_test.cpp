// MapPanel: its buttons set the requests LiveMapping carries out; Add to map and Save map are
// offered only once there is a map, and Build / Add give way to the progress bar while the
// worker runs.
#include "app/viewer/MapPanel.hpp"

#include <gtest/gtest.h>

#include <optional>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

const cv::Rect2f kPlace(950, 0, 330, 520);

// Where the (enabled) button `label` of the Map window is (as in CalibrationPanel_test).
std::optional<ImVec2> findButton(test::ImGuiTestContext& ui, const std::function<void()>& draw,
                                 const char* label) {
  ImGuiWindow* w = test::ImGuiTestContext::window("Map");
  if (!w) return std::nullopt;
  const ImGuiID id = w->GetID(label);
  ImGuiIO& io = ImGui::GetIO();
  std::optional<ImVec2> found;
  for (float y = w->Pos.y + 20; y < w->Pos.y + w->Size.y && !found; y += 6)
    for (float x = w->Pos.x + 5; x < w->Pos.x + w->Size.x && !found; x += 12) {
      io.MousePos = ImVec2(x, y);
      ui.frame(draw);
      if (GImGui->HoveredId == id) found = ImVec2(x, y);
    }
  io.MousePos = ImVec2(-1, -1);
  ui.frame(draw);
  return found;
}

}  // namespace

TEST(MapPanel, ButtonsSetRequestsOnceTheyApply) {
  test::ImGuiTestContext ui;
  MapState state;
  state.active = true;
  state.fiducial = "marker DICT_6X6_250:23:0.2";
  auto draw = [&] { drawMapPanel(state, kPlace); };
  ui.frame(draw);
  ImGuiWindow* w = test::ImGuiTestContext::window("Map");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.x, kPlace.x);

  const auto capture = findButton(ui, draw, "Capture reference");
  ASSERT_TRUE(capture);
  ui.clickAt(capture->x, capture->y, draw);
  EXPECT_TRUE(state.captureRequested);
  const auto build = findButton(ui, draw, "Build map");
  ASSERT_TRUE(build);
  ui.clickAt(build->x, build->y, draw);
  EXPECT_TRUE(state.buildRequested);
  // No map yet: Add to map and Save map are disabled (clicking them requests nothing).
  for (const char* label : {"Add to map", "Save map"}) {
    const auto disabled = findButton(ui, draw, label);
    ASSERT_TRUE(disabled) << label;
    ui.clickAt(disabled->x, disabled->y, draw);
  }
  EXPECT_FALSE(state.addRequested);
  EXPECT_FALSE(state.saveRequested);

  // Two captures and a map: Add and Save appear; the pair's warning is shown.
  state.captures = {MapCapture{0, 0.0, "marker", 0.1, true, "", 0},
                    MapCapture{1, 0.03, "marker", 0.1, true, "", 0}};
  state.pairs = {MapCapturePair{0, 1, 0.004, 0.2, "too close to triangulate (under 10 mm)"}};
  state.mapReferences = 2;
  state.mapPoints = 500;
  const auto add = findButton(ui, draw, "Add to map");
  ASSERT_TRUE(add);
  ui.clickAt(add->x, add->y, draw);
  EXPECT_TRUE(state.addRequested);
  const auto save = findButton(ui, draw, "Save map");
  ASSERT_TRUE(save);
  ui.clickAt(save->x, save->y, draw);
  EXPECT_TRUE(state.saveRequested);
  const auto clear = findButton(ui, draw, "Clear");
  ASSERT_TRUE(clear);
  ui.clickAt(clear->x, clear->y, draw);
  EXPECT_TRUE(state.clearRequested);

  // While the worker runs: a progress bar instead of Build / Add, Save disabled.
  state.buildRequested = state.addRequested = state.saveRequested = false;
  state.working = true;
  state.workLabel = "building the map";
  state.progress = 0.5f;
  EXPECT_FALSE(findButton(ui, draw, "Build map"));
  EXPECT_FALSE(findButton(ui, draw, "Add to map"));
  const auto busySave = findButton(ui, draw, "Save map");
  ASSERT_TRUE(busySave);
  ui.clickAt(busySave->x, busySave->y, draw);
  EXPECT_FALSE(state.saveRequested);
  EXPECT_TRUE(findButton(ui, draw, "Capture reference"));
}

// Unprepared (no marker or board): the Baseline field (its + button steps it by 1 cm) and the
// motion since the first capture; both go once the map is built.
TEST(MapPanel, UnpreparedOffersTheBaselineField) {
  test::ImGuiTestContext ui;
  MapState state;
  state.active = true;
  state.unprepared = true;
  state.fiducial = "none (unprepared: own matches)";
  state.captures = {MapCapture{0, 0.0, "matches", -1.0, false, "", 0}};
  state.motion = "420 keypoint matches, 400 fit the essential matrix";
  state.motionUsable = true;
  state.motionFrame = 12;
  auto draw = [&] { drawMapPanel(state, kPlace); };
  ui.frame(draw);
  ImGuiWindow* w = test::ImGuiTestContext::window("Map");
  ASSERT_NE(w, nullptr);
  // InputDouble's + button: "+" in the ID scope of the field's label.
  const ImGuiID plus = ImHashStr("+", 0, w->GetID("baseline (m)"));
  std::optional<ImVec2> at;
  ImGuiIO& io = ImGui::GetIO();
  for (float y = w->Pos.y + 20; y < w->Pos.y + w->Size.y && !at; y += 4)
    for (float x = w->Pos.x + 5; x < w->Pos.x + w->Size.x && !at; x += 6) {
      io.MousePos = ImVec2(x, y);
      ui.frame(draw);
      if (GImGui->HoveredId == plus) at = ImVec2(x, y);
    }
  ASSERT_TRUE(at) << "no + button of the baseline field";
  ui.clickAt(at->x, at->y, draw);
  ui.clickAt(at->x, at->y, draw);
  EXPECT_NEAR(state.baselineMetres, 0.02, 1e-12);
  const auto build = findButton(ui, draw, "Build map");
  ASSERT_TRUE(build);
  ui.clickAt(build->x, build->y, draw);
  EXPECT_TRUE(state.buildRequested);
  // Built: the field is gone.
  state.mapReferences = 2;
  ui.frame(draw);
  bool fieldShown = false;
  for (float y = w->Pos.y + 20; y < w->Pos.y + w->Size.y && !fieldShown; y += 4)
    for (float x = w->Pos.x + 5; x < w->Pos.x + w->Size.x && !fieldShown; x += 6) {
      io.MousePos = ImVec2(x, y);
      ui.frame(draw);
      fieldShown = GImGui->HoveredId == plus;
    }
  EXPECT_FALSE(fieldShown);
}
