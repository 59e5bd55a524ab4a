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
  // Placement: on the tracked scene (when there is one) or by hand; typing a size or an offset
  // takes the object off the scene's choice.
  if (edit.scene) {
    ImGui::Checkbox("On the scene", &settings.onScene);
    ImGui::SameLine();
    ImGui::Checkbox("Scene size", &settings.sizeFromScene);
  }
  double size = settings.size;
  if (ImGui::InputDouble("Size (m)", &size, 0.01, 0.1, "%.3f") && size > 0) {
    settings.size = size;
    settings.sizeFromScene = false;
  }
  bool moved = ImGui::InputDouble("Offset x", &settings.offset.x(), 0.01, 0.1, "%.3f");
  moved |= ImGui::InputDouble("Offset y", &settings.offset.y(), 0.01, 0.1, "%.3f");
  moved |= ImGui::InputDouble("Offset z", &settings.offset.z(), 0.01, 0.1, "%.3f");
  if (moved) settings.onScene = false;
  settings.applyScene(edit.scene);
  ImGui::SliderFloat("Line (px)", &settings.lineWidthPx, 1.0f, 10.0f, "%.1f");
  ImGui::PopItemWidth();
  ImGui::Checkbox("Vertex dots", &settings.vertexDots);
  ImGui::SameLine();
  ImGui::Checkbox("Epipolar", &settings.showEpipolarLines);
  // The tracker's debug layers (`--debug-overlay`): all three at once, or each on its own.
  bool debug = settings.showCorners && settings.showMatches && settings.showLabels;
  if (ImGui::Checkbox("Debug overlay", &debug)) settings.setDebugLayers(debug);
  ImGui::Checkbox("Corners", &settings.showCorners);
  ImGui::SameLine();
  ImGui::Checkbox("Matches", &settings.showMatches);
  ImGui::SameLine();
  ImGui::Checkbox("Labels", &settings.showLabels);
  ImGui::End();
}

}  // namespace reftrack::app
