#include "render/gl/GlLoader.hpp"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack::render;

using GlLoaderTest = reftrack::test::HeadlessGlTest;

TEST_F(GlLoaderTest, DescriptionNamesVersionAndRenderer) {
  const std::string description = currentGlDescription();
  EXPECT_NE(description.find(" | "), std::string::npos);
  EXPECT_EQ(description, context_->description());
  EXPECT_NE(glGenFramebuffers, nullptr);
}

TEST(GlLoader, LoaderThatFindsNothingIsAnError) {
  const GlProcLoader nothing = [](const char*) -> void (*)() { return nullptr; };
  EXPECT_THROW(loadGlFunctions(nothing), reftrack::Error);
}
