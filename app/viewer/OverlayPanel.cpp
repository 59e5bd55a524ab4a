#include "app/viewer/OverlayPanel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

namespace reftrack::app {

void drawOverlayPanel(OverlaySettings& settings, OverlayPanelEdit& edit,
                      const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Overlay");
  ImGui::PushItemWidth(150);
  if (!settings.modelPath.empty()) {
    edit.useModel = true;
    if (edit.modelPath.empty()) edit.modelPath = settings.modelPath;
  }
  int object = edit.useModel ? 1 : 0;
  ImGui::RadioButton("Cube", &object, 0);
  ImGui::SameLine();
  ImGui::RadioButton("OBJ model", &object, 1);
  edit.useModel = object == 1;
  if (!edit.useModel) {
    settings.modelPath.clear();
  } else if (ImGui::InputText("Model", &edit.modelPath, ImGuiInputTextFlags_EnterReturnsTrue)) {
    settings.modelPath = edit.modelPath;
    edit.message.clear();
  }
  if (!edit.message.empty()) ImGui::TextWrapped("%s", edit.message.c_str());
  double size = settings.size;
  if (ImGui::InputDouble("Size (m)", &size, 0.01, 0.1, "%.3f") && size > 0) settings.size = size;
  ImGui::InputDouble("Offset x", &settings.offset.x(), 0.01, 0.1, "%.3f");
  ImGui::InputDouble("Offset y", &settings.offset.y(), 0.01, 0.1, "%.3f");
  ImGui::InputDouble("Offset z", &settings.offset.z(), 0.01, 0.1, "%.3f");
  ImGui::SliderFloat("Line (px)", &settings.lineWidthPx, 1.0f, 10.0f, "%.1f");
  ImGui::PopItemWidth();
  ImGui::Checkbox("Vertex dots", &settings.vertexDots);
  ImGui::SameLine();
  ImGui::Checkbox("Labels", &settings.showLabels);
  ImGui::Checkbox("Corners", &settings.showCorners);
  ImGui::SameLine();
  ImGui::Checkbox("Matches", &settings.showMatches);
  ImGui::SameLine();
  ImGui::Checkbox("Epipolar", &settings.showEpipolarLines);
  ImGui::End();
}

}  // namespace reftrack::app
