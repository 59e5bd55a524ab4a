#include "app/viewer/RecordPanel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

namespace reftrack::app {

void drawRecordPanel(RecordState& state, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Record");
  ImGui::PushItemWidth(-60);
  ImGui::InputText("Output", &state.path,
                   state.recording ? ImGuiInputTextFlags_ReadOnly : ImGuiInputTextFlags_None);
  ImGui::PopItemWidth();
  if (!state.recording) {
    if (ImGui::Button("Start")) state.startRequested = true;
  } else {
    if (ImGui::Button("Stop")) state.stopRequested = true;
    ImGui::SameLine();
    ImGui::Text("recording: %d frames", state.framesWritten);
  }
  if (!state.message.empty()) ImGui::TextWrapped("%s", state.message.c_str());
  ImGui::End();
}

}  // namespace reftrack::app
