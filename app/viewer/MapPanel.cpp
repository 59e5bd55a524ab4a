#include "app/viewer/MapPanel.hpp"

#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdint>

namespace reftrack::app {

namespace {

// A button that is drawn disabled (and requests nothing) when `enabled` is false.
bool button(const char* label, bool enabled) {
  if (!enabled) ImGui::BeginDisabled();
  const bool pressed = ImGui::Button(label);
  if (!enabled) ImGui::EndDisabled();
  return pressed && enabled;
}

}  // namespace

void drawMapPanel(MapState& state, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Map");
  ImGui::TextDisabled("world frame: %s", state.fiducial.empty() ? "-" : state.fiducial.c_str());
  if (state.unprepared && state.mapReferences == 0)
    ImGui::TextWrapped(
        "No marker: capture the scene from two places a hand's width apart (move the camera "
        "sideways, do not only turn it), type how far it moved, Build map.");
  if (button("Capture reference", true)) state.captureRequested = true;
  ImGui::SameLine();
  if (button("Clear", !state.working && !state.captures.empty())) state.clearRequested = true;

  // The captures: thumbnails in rows, framed green once in the map.
  const float width =
      state.thumbnailSize.width > 0 ? static_cast<float>(state.thumbnailSize.width) : 96.0f;
  const float height =
      state.thumbnailSize.height > 0 ? static_cast<float>(state.thumbnailSize.height) : 61.0f;
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const int perRow = std::max(
      1, static_cast<int>((ImGui::GetContentRegionAvail().x + spacing) / (width + spacing)));
  const int n = static_cast<int>(state.captures.size());
  if (n == 0) ImGui::TextWrapped("no reference captured yet");
  for (int i = 0; i < n; ++i) {
    const MapCapture& c = state.captures[static_cast<std::size_t>(i)];
    if (i % perRow != 0) ImGui::SameLine();
    ImGui::BeginGroup();
    const ImVec2 topLeft = ImGui::GetCursorScreenPos();
    if (c.thumbnail != 0)
      ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(c.thumbnail)),
                   ImVec2(width, height));
    else
      ImGui::Dummy(ImVec2(width, height));
    ImGui::GetWindowDrawList()->AddRect(
        topLeft, ImVec2(topLeft.x + width, topLeft.y + height),
        c.inMap ? IM_COL32(80, 220, 80, 255) : IM_COL32(110, 110, 110, 255), 0.0f, 0,
        c.inMap ? 2.0f : 1.0f);
    ImGui::Text("%d: frame %d", i, c.frameIndex);
    ImGui::TextDisabled("%s", c.poseFrom.c_str());
    ImGui::EndGroup();
  }
  if (!state.pairs.empty() && ImGui::BeginTable("pairs", 3, ImGuiTableFlags_SizingFixedFit)) {
    for (const MapCapturePair& p : state.pairs) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%d-%d", p.a, p.b);
      ImGui::TableNextColumn();
      ImGui::Text("%.0f mm", p.distanceMetres * 1000.0);
      ImGui::TableNextColumn();
      ImGui::Text("%.1f deg", p.angleDeg);
      if (!p.warning.empty()) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TableNextColumn();
        ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.2f, 1.0f), "%s", p.warning.c_str());
      }
    }
    ImGui::EndTable();
  }
  for (const MapCapture& c : state.captures)
    if (!c.note.empty()) ImGui::TextWrapped("frame %d not added: %s", c.frameIndex, c.note.c_str());
  // Unprepared: the motion since the first capture, green when the two views can start a map.
  if (state.unprepared && state.mapReferences == 0 && !state.captures.empty() &&
      !state.motion.empty()) {
    const ImVec4 colour =
        state.motionUsable ? ImVec4(0.45f, 0.9f, 0.45f, 1.0f) : ImVec4(1.0f, 0.75f, 0.2f, 1.0f);
    ImGui::PushStyleColor(ImGuiCol_Text, colour);
    ImGui::TextWrapped("%s since capture 0 (frame %d): %s",
                       state.motionUsable ? "ready" : "not yet", state.motionFrame,
                       state.motion.c_str());
    ImGui::PopStyleColor();
  }
  if (state.unprepared && state.mapReferences == 0) {
    ImGui::SetNextItemWidth(120.0f);
    ImGui::InputDouble("baseline (m)", &state.baselineMetres, 0.01, 0.05, "%.3f");
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("how far the camera moved between the two captures (metres)");
  }

  ImGui::Separator();
  if (state.working) {
    ImGui::TextUnformatted(state.workLabel.c_str());
    ImGui::ProgressBar(state.progress, ImVec2(-1, 0), state.progressText.c_str());
  } else {
    if (button("Build map", true)) state.buildRequested = true;
    ImGui::SameLine();
    if (button("Add to map", state.mapReferences > 0)) state.addRequested = true;
  }
  if (state.mapReferences > 0)
    ImGui::Text("map: %d references, %zu points%s", state.mapReferences, state.mapPoints,
                state.tracking ? ", tracking" : "");
  // The folder to save to, with the button beside it.
  ImGui::SetNextItemWidth(
      std::max(60.0f, ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("Save map").x -
                          2 * ImGui::GetStyle().FramePadding.x - ImGui::GetStyle().ItemSpacing.x));
  ImGui::InputText("##folder", &state.savePath);
  ImGui::SameLine();
  if (button("Save map", state.mapReferences > 0 && !state.working)) state.saveRequested = true;
  if (!state.message.empty()) {
    if (state.messageIsError) ImGui::PushStyleColor(ImGuiCol_Text, ImVec4(1.0f, 0.45f, 0.4f, 1.0f));
    ImGui::TextWrapped("%s", state.message.c_str());
    if (state.messageIsError) ImGui::PopStyleColor();
  }
  ImGui::End();
}

}  // namespace reftrack::app
