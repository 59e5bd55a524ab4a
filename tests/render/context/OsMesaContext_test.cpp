#include "render/context/OsMesaContext.hpp"

#include <gtest/gtest.h>

#include "render/context/ContextTestSupport.hpp"

using namespace reftrack::render;

TEST(OsMesaContext, CreatesCoreContextThatClearsAndReadsBack) {
  OsMesaContext context;
  EXPECT_EQ(context.backendName(), "osmesa");
  std::cout << "OSMesa: " << context.description() << "\n";
  EXPECT_NE(context.description().find("Core"), std::string::npos) << context.description();
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  EXPECT_GE(major * 10 + minor, 33);
  // 8-bit colour: a clear colour given as k/255 must come back as exactly k.
  const auto pixel = reftrack::test::clearAndReadBack(200, 100, 50);
  EXPECT_EQ(pixel[0], 200);
  EXPECT_EQ(pixel[1], 100);
  EXPECT_EQ(pixel[2], 50);
  EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST(OsMesaContext, TwoContextsInSequenceBothWork) {
  for (int value : {10, 240}) {
    OsMesaContext context;
    EXPECT_EQ(reftrack::test::clearAndReadBack(value, value, value)[1], value);
  }
}
