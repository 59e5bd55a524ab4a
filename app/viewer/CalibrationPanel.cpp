#include "app/viewer/CalibrationPanel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>

namespace reftrack::app {

void drawCalibrationPanel(CalibrationState& state, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Calibration");
  ImGui::PushItemWidth(-60);
  if (ImGui::InputText("Board", &state.boardText, ImGuiInputTextFlags_EnterReturnsTrue))
    state.applyBoardRequested = true;
  ImGui::PopItemWidth();
  if (ImGui::Button("Apply board")) state.applyBoardRequested = true;
  ImGui::SameLine();
  ImGui::TextDisabled("in use: %s", state.board.empty() ? "-" : state.board.c_str());

  ImGui::Separator();
  if (ImGui::Button("Capture view")) state.captureRequested = true;
  ImGui::SameLine();
  if (ImGui::Button("Clear views")) state.clearRequested = true;
  ImGui::Checkbox("auto-capture every", &state.autoCapture);
  ImGui::SameLine();
  ImGui::PushItemWidth(90);
  if (ImGui::InputInt("frames", &state.autoCaptureEvery))
    state.autoCaptureEvery = std::clamp(state.autoCaptureEvery, 1, 10000);
  ImGui::PopItemWidth();
  if (state.currentCorners < 0)
    ImGui::Text("board: not analysed yet");
  else if (state.currentCorners == 0)
    ImGui::Text("board: not found in the latest frame");
  else
    ImGui::Text("board: %d corners found", state.currentCorners);
  ImGui::Text("captured %d, rejected %d%s", state.captured, state.rejected,
              state.capturePending ? "  (capturing...)" : "");
  if (!state.lastRejection.empty())
    ImGui::TextWrapped("last rejected: %s", state.lastRejection.c_str());
  ImGui::ProgressBar(static_cast<float>(state.coverage), ImVec2(-70, 0), nullptr);
  ImGui::SameLine(0, 4);
  ImGui::Text("coverage");

  ImGui::Separator();
  if (state.calibrating) {
    ImGui::BeginDisabled();
    ImGui::Button("Calibrating...");
    ImGui::EndDisabled();
  } else if (ImGui::Button("Calibrate")) {
    state.calibrateRequested = true;
  }
  if (state.result) {
    const CalibrationResult& r = *state.result;
    ImGui::Text("RMS %.4f px from %zu views", r.rmsPx, r.views.size());
    ImGui::Text("fx %.2f  fy %.2f", r.camera.fx(), r.camera.fy());
    ImGui::Text("cx %.2f  cy %.2f", r.camera.cx(), r.camera.cy());
    if (ImGui::CollapsingHeader("Per-view errors")) {
      for (const CalibrationViewError& v : r.views)
        ImGui::Text("%-10s %3d corners  %.4f px", v.label.c_str(), v.corners, v.rmsPx);
    }
    ImGui::PushItemWidth(-60);
    ImGui::InputText("File", &state.savePath);
    ImGui::PopItemWidth();
    if (ImGui::Button("Save camera.yml")) state.saveRequested = true;
    ImGui::SameLine();
    if (ImGui::Button("Use for tracking")) state.useForTrackingRequested = true;
    if (state.usedForTracking) ImGui::TextDisabled("in use for tracking");
  }
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::End();
}

}  // namespace reftrack::app
