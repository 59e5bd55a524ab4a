#pragma once
// A GL-free ImGui context for panel tests: fonts built, fixed display size, no renderer (draw
// data is produced and discarded). clickAt() plays the press/release frames of a mouse click.
#include <imgui.h>
#include <imgui_internal.h>

#include <functional>

namespace reftrack::test {

class ImGuiTestContext {
 public:
  ImGuiTestContext() {
    ImGui::CreateContext();
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.DisplaySize = ImVec2(1280, 720);
    io.DeltaTime = 1.0f / 30;
    unsigned char* pixels = nullptr;
    int w = 0, h = 0;
    io.Fonts->GetTexDataAsRGBA32(&pixels, &w, &h);  // builds the atlas
  }
  ~ImGuiTestContext() { ImGui::DestroyContext(); }
  ImGuiTestContext(const ImGuiTestContext&) = delete;
  ImGuiTestContext& operator=(const ImGuiTestContext&) = delete;

  void frame(const std::function<void()>& draw) {
    ImGui::NewFrame();
    draw();
    ImGui::Render();
  }
  // Hover, press, release at (x, y), then move away; the widget sees one click.
  void clickAt(float x, float y, const std::function<void()>& draw) {
    ImGuiIO& io = ImGui::GetIO();
    io.MousePos = ImVec2(x, y);
    frame(draw);
    io.MouseDown[0] = true;
    frame(draw);
    io.MouseDown[0] = false;
    frame(draw);
    io.MousePos = ImVec2(-1, -1);
    frame(draw);
  }
  static ImGuiWindow* window(const char* name) { return ImGui::FindWindowByName(name); }
};

}  // namespace reftrack::test
