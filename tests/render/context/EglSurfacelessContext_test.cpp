#include "render/context/EglSurfacelessContext.hpp"

#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/context/ContextTestSupport.hpp"

using namespace reftrack::render;

TEST(EglSurfacelessContext, CreatesCoreContextThatClearsAndReadsBack) {
  std::unique_ptr<EglSurfacelessContext> context;
  try {
    context = std::make_unique<EglSurfacelessContext>();
  } catch (const reftrack::Error& e) {
    GTEST_SKIP() << "EGL surfaceless unavailable on this machine: " << e.what();
  }
  EXPECT_EQ(context->backendName(), "egl-surfaceless");
  std::cout << "EGL surfaceless: " << context->description() << "\n";
  const auto pixel = reftrack::test::clearAndReadBack(30, 60, 90);
  EXPECT_EQ(pixel[0], 30);
  EXPECT_EQ(pixel[1], 60);
  EXPECT_EQ(pixel[2], 90);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}
