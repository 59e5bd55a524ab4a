#pragma once
// GlfwWindowContext: a GLFW window with an OpenGL 3.3 core context (the viewer). Throws
// reftrack::Error "no display (DISPLAY unset) ..." when there is no window system to open it on.
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "render/context/GlContext.hpp"

struct GLFWwindow;

namespace reftrack::render {

struct WindowOptions {
  std::string title = "reftrack";
  cv::Size size{1280, 720};  // window size in screen coordinates
  bool vsync = true;         // swap interval 1 (else 0)
  bool visible = true;
  void check() const;  // throws reftrack::Error naming the bad field
};

class GlfwWindowContext final : public GlContext {
 public:
  // Opens the window, makes its context current and loads the GL functions.
  explicit GlfwWindowContext(const WindowOptions& options = {});
  ~GlfwWindowContext() override;

  void makeCurrent() override;

  cv::Size framebufferSize() const;  // in pixels (differs from the window size on HiDPI)
  void swapBuffers();
  bool shouldClose() const;
  void setShouldClose(bool close);
  void pollEvents();
  GLFWwindow* window() const { return window_; }  // for input handling and ImGui

 private:
  GLFWwindow* window_ = nullptr;
};

}  // namespace reftrack::render
