#include "render/context/GlfwWindowContext.hpp"

#include <gtest/gtest.h>

#include <cstdlib>

#include "engine/core/Error.hpp"
#include "render/context/ContextTestSupport.hpp"

using namespace reftrack::render;

TEST(GlfwWindowContext, WithoutDisplayGivesClearError) {
  const char* display = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  if ((display && *display) || (wayland && *wayland))
    GTEST_SKIP() << "a display is available; the no-display error path cannot be exercised";
  try {
    GlfwWindowContext window;
    FAIL() << "expected an error without a display";
  } catch (const reftrack::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no display (DISPLAY unset)"), std::string::npos)
        << e.what();
  }
}

TEST(GlfwWindowContext, RejectsEmptyWindowSize) {
  WindowOptions options;
  options.size = {0, 480};
  EXPECT_THROW(options.check(), reftrack::Error);
}

TEST(GlfwWindowContext, OpensHiddenWindowWhenDisplayPresent) {
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display) GTEST_SKIP() << "DISPLAY unset: run under xvfb-run to test a window";
  WindowOptions options;
  options.size = {64, 48};
  options.visible = false;
  options.vsync = false;
  GlfwWindowContext window(options);
  EXPECT_EQ(window.backendName(), "glfw-window");
  std::cout << "GLFW: " << window.description() << "\n";
  EXPECT_GT(window.framebufferSize().width, 0);
  EXPECT_FALSE(window.shouldClose());
  window.setShouldClose(true);
  EXPECT_TRUE(window.shouldClose());
  EXPECT_EQ(reftrack::test::clearAndReadBack(11, 22, 33)[1], 22);
  window.swapBuffers();
}
