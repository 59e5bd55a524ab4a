// CalibrationPanel: its buttons set the requests LiveCalibration carries out; the result rows
// (Save, Use for tracking) appear only once there is a result, and Calibrate cannot be asked
// twice while a calibration runs.
#include "app/viewer/CalibrationPanel.hpp"

#include <gtest/gtest.h>

#include <optional>

#include "ImGuiTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::app;

namespace {

const cv::Rect2f kPlace(950, 0, 330, 520);

// Where the button `label` of the Calibration window is: the mouse is moved over the window on a
// 12 x 6 px grid (buttons are at least 19 px high and 30 px wide) until ImGui reports that widget
// hovered. nullopt when the window has no such (enabled) button.
std::optional<ImVec2> findButton(test::ImGuiTestContext& ui, const std::function<void()>& draw,
                                 const char* label) {
  ImGuiWindow* w = test::ImGuiTestContext::window("Calibration");
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

CalibrationResult someResult() {
  CalibrationResult r;
  Eigen::Matrix3d K;
  K << 600, 0, 320, 0, 600, 240, 0, 0, 1;
  r.camera = PinholeCamera(K, {640, 480});
  r.rmsPx = 0.12;
  r.views = {{"view 1", 54, 0.1}, {"view 2", 54, 0.14}};
  return r;
}

}  // namespace

TEST(CalibrationPanel, ButtonsSetRequests) {
  test::ImGuiTestContext ui;
  CalibrationState state;
  state.active = true;
  state.board = state.boardText;
  auto draw = [&] { drawCalibrationPanel(state, kPlace); };
  ui.frame(draw);
  ImGuiWindow* w = test::ImGuiTestContext::window("Calibration");
  ASSERT_NE(w, nullptr);
  EXPECT_EQ(w->Pos.x, kPlace.x);
  EXPECT_EQ(w->Size.y, kPlace.height);

  const auto capture = findButton(ui, draw, "Capture view");
  ASSERT_TRUE(capture);
  EXPECT_FALSE(state.captureRequested);  // hovering is not clicking
  ui.clickAt(capture->x, capture->y, draw);
  EXPECT_TRUE(state.captureRequested);

  const auto clear = findButton(ui, draw, "Clear views");
  ASSERT_TRUE(clear);
  EXPECT_GT(clear->x, capture->x);  // on the same row, to the right
  ui.clickAt(clear->x, clear->y, draw);
  EXPECT_TRUE(state.clearRequested);

  const auto apply = findButton(ui, draw, "Apply board");
  ASSERT_TRUE(apply);
  ui.clickAt(apply->x, apply->y, draw);
  EXPECT_TRUE(state.applyBoardRequested);

  const auto autoCapture = findButton(ui, draw, "auto-capture every");
  ASSERT_TRUE(autoCapture);
  ui.clickAt(autoCapture->x, autoCapture->y, draw);
  EXPECT_TRUE(state.autoCapture);

  // No result yet: nothing to save or use.
  EXPECT_FALSE(findButton(ui, draw, "Save camera.yml"));
  EXPECT_FALSE(findButton(ui, draw, "Use for tracking"));
  const auto calibrate = findButton(ui, draw, "Calibrate");
  ASSERT_TRUE(calibrate);
  ui.clickAt(calibrate->x, calibrate->y, draw);
  EXPECT_TRUE(state.calibrateRequested);
}

TEST(CalibrationPanel, ResultRowsAndRunningCalibration) {
  test::ImGuiTestContext ui;
  CalibrationState state;
  state.active = true;
  auto draw = [&] { drawCalibrationPanel(state, kPlace); };
  ui.frame(draw);
  const auto calibrate = findButton(ui, draw, "Calibrate");
  ASSERT_TRUE(calibrate);
  // While calibrating the button is a disabled "Calibrating...": clicking it requests nothing.
  state.calibrating = true;
  ui.frame(draw);
  EXPECT_FALSE(findButton(ui, draw, "Calibrate"));
  ui.clickAt(calibrate->x, calibrate->y, draw);
  EXPECT_FALSE(state.calibrateRequested);

  state.calibrating = false;
  state.result = someResult();
  ui.frame(draw);
  const auto save = findButton(ui, draw, "Save camera.yml");
  ASSERT_TRUE(save);
  ui.clickAt(save->x, save->y, draw);
  EXPECT_TRUE(state.saveRequested);
  const auto use = findButton(ui, draw, "Use for tracking");
  ASSERT_TRUE(use);
  EXPECT_GT(use->x, save->x);
  ui.clickAt(use->x, use->y, draw);
  EXPECT_TRUE(state.useForTrackingRequested);
}
