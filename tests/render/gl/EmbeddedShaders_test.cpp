#include "render/gl/EmbeddedShaders.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "TestPaths.hpp"
#include "engine/core/Error.hpp"

using namespace reftrack;
using namespace reftrack::render;

TEST(EmbeddedShaders, MatchTheFilesInShadersFolder) {
  ASSERT_FALSE(embeddedShaders().empty());
  for (const EmbeddedShader& shader : embeddedShaders()) {
    std::ifstream file(test::sourceDir() / "shaders" / shader.fileName);
    ASSERT_TRUE(file) << shader.fileName;
    std::stringstream text;
    text << file.rdbuf();
    EXPECT_EQ(text.str(), shader.source) << shader.fileName << " is stale: re-run cmake";
    EXPECT_EQ(embeddedShaderSource(shader.fileName), shader.source);
  }
}

TEST(EmbeddedShaders, EveryShaderFileIsEmbedded) {
  for (const auto& entry : std::filesystem::directory_iterator(test::sourceDir() / "shaders")) {
    const std::string name = entry.path().filename().string();
    EXPECT_NO_THROW(embeddedShaderSource(name)) << name << " is not in REFTRACK_SHADER_FILES";
  }
}

TEST(EmbeddedShaders, UnknownNameIsAnError) {
  try {
    embeddedShaderSource("missing.frag");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("shaders/missing.frag"), std::string::npos);
  }
}
