#include "app/viewer/SourcePanel.hpp"

#include <imgui.h>

#include <algorithm>

namespace reftrack::app {

void drawSourcePanel(SourceState& state, const cv::Rect2f& placement) {
  ImGui::SetNextWindowPos({placement.x, placement.y}, ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize({placement.width, placement.height}, ImGuiCond_FirstUseEver);
  ImGui::Begin("Source");
  ImGui::TextWrapped("%s", state.description.c_str());
  if (state.frameCount)
    ImGui::Text("frame %d / %d  (%.1f fps)", state.currentIndex, *state.frameCount, state.fps);
  else
    ImGui::Text("frame %d  (%.1f fps, dropped %zu)", state.currentIndex, state.fps,
                state.droppedFrames);
  if (ImGui::Button(state.playing ? "Pause" : "Play")) state.playing = !state.playing;
  ImGui::SameLine();
  if (ImGui::Button("Step")) {
    state.playing = false;
    state.stepRequested = true;
  }
  ImGui::SameLine();
  ImGui::Checkbox("Loop", &state.loop);
  if (state.ended) {
    ImGui::SameLine();
    ImGui::TextUnformatted("(end)");
  }
  if (state.seekable && state.frameCount && *state.frameCount > 0) {
    int target = std::max(0, state.currentIndex);
    if (ImGui::SliderInt("Seek", &target, 0, *state.frameCount - 1)) state.seekRequest = target;
  }
  ImGui::SliderFloat("Speed", &state.speed, 0.1f, 4.0f, "%.2fx");
  ImGui::End();
}

}  // namespace reftrack::app
