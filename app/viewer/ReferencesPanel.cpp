#include "app/viewer/ReferencesPanel.hpp"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace reftrack::app {

void ReferencesState::addFrame(const ReferencesFrame& frame) {
  referenceA = frame.referenceA;
  referenceB = frame.referenceB;
  if (!frame.relocalisationAttempted) return;
  ++attempts;
  if (frame.relocalisationSucceeded) ++successes;
  attemptMs.push_back(frame.relocalisationMs);
  // The panel shows recent attempts: a bounded history keeps a long session's memory flat.
  if (attemptMs.size() > 1000) attemptMs.erase(attemptMs.begin(), attemptMs.begin() + 500);
  lastMessage = frame.relocalisationMessage;
}

double ReferencesState::lastMs() const { return attemptMs.empty() ? NAN : attemptMs.back(); }

double ReferencesState::medianMs() const {
  if (attemptMs.empty()) return NAN;
  std::vector<double> v = attemptMs;
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

void drawReferencesPanel(const ReferencesState& state, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("References");
  const int n = static_cast<int>(state.names.size());
  if (state.referenceA >= 0)
    ImGui::Text("%d references, in use: %d + %d", n, state.referenceA, state.referenceB);
  else
    ImGui::Text("%d references, none in use", n);
  if (state.attempts == 0) {
    ImGui::Text("relocalisation: no attempt yet");
  } else {
    ImGui::Text("relocalisation: %d of %d succeeded", state.successes, state.attempts);
    ImGui::Text("  last %.1f ms, median %.1f ms", state.lastMs(), state.medianMs());
    ImGui::TextWrapped("  %s", state.lastMessage.c_str());
  }
  // Thumbnails in rows; the pair in use framed in yellow.
  const float width =
      state.thumbnailSize.width > 0 ? static_cast<float>(state.thumbnailSize.width) : 96.0f;
  const float height =
      state.thumbnailSize.height > 0 ? static_cast<float>(state.thumbnailSize.height) : 72.0f;
  const float spacing = ImGui::GetStyle().ItemSpacing.x;
  const int perRow = std::max(
      1, static_cast<int>((ImGui::GetContentRegionAvail().x + spacing) / (width + spacing)));
  for (int i = 0; i < n; ++i) {
    if (i % perRow != 0) ImGui::SameLine();
    ImGui::BeginGroup();
    const ImVec2 topLeft = ImGui::GetCursorScreenPos();
    const unsigned int texture = i < static_cast<int>(state.thumbnails.size())
                                     ? state.thumbnails[static_cast<std::size_t>(i)]
                                     : 0u;
    if (texture != 0)
      ImGui::Image(reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(texture)),
                   ImVec2(width, height));
    else
      ImGui::Dummy(ImVec2(width, height));
    const bool inUse = i == state.referenceA || i == state.referenceB;
    ImGui::GetWindowDrawList()->AddRect(
        topLeft, ImVec2(topLeft.x + width, topLeft.y + height),
        inUse ? IM_COL32(255, 220, 0, 255) : IM_COL32(110, 110, 110, 255), 0.0f, 0,
        inUse ? 3.0f : 1.0f);
    ImGui::Text("%s%d %s", inUse ? "* " : "", i, state.names[static_cast<std::size_t>(i)].c_str());
    ImGui::EndGroup();
  }
  ImGui::End();
}

}  // namespace reftrack::app
