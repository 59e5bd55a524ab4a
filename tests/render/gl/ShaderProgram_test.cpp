#include "render/gl/ShaderProgram.hpp"

#include <glad/gl.h>
#include <gtest/gtest.h>

#include "engine/core/Error.hpp"
#include "render/RenderTestSupport.hpp"

using namespace reftrack;
using namespace reftrack::render;

using ShaderProgramTest = test::HeadlessGlTest;

namespace {
const char* kVertex = "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n";
const char* kFragment = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n";
}  // namespace

TEST_F(ShaderProgramTest, EveryEmbeddedShaderPairLinks) {
  for (const auto& [vertex, fragment] : std::vector<std::pair<std::string, std::string>>{
           {"textured_mesh.vert", "textured_mesh.frag"},
           {"lit_mesh.vert", "lit_mesh.frag"},
           {"pixel_colour.vert", "pixel_colour.frag"},
           {"video_background.vert", "video_background.frag"}}) {
    const ShaderProgram program = ShaderProgram::fromFiles(vertex, fragment);
    EXPECT_NE(program.id(), 0u) << vertex;
  }
}

TEST_F(ShaderProgramTest, CompileErrorNamesFileAndQuotesLog) {
  try {
    ShaderProgram("broken.vert", "#version 330 core\nvoid main() { undefined_thing; }\n", "ok.frag",
                  kFragment);
    FAIL() << "expected a compile error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("broken.vert failed to compile"), std::string::npos) << message;
    EXPECT_NE(message.find("undefined_thing"), std::string::npos) << message;
  }
}

TEST_F(ShaderProgramTest, LinkErrorNamesBothFiles) {
  // Each stage compiles alone, but the fragment shader has no main(): only the linker sees it.
  const char* fragment = "#version 330 core\nout vec4 c;\nvoid helper() { c = vec4(1.0); }\n";
  try {
    ShaderProgram("a.vert", kVertex, "b.frag", fragment);
    FAIL() << "expected a link error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("a.vert + b.frag failed to link"), std::string::npos)
        << e.what();
  }
}

TEST_F(ShaderProgramTest, UnknownEmbeddedFileIsAnError) {
  EXPECT_THROW(ShaderProgram::fromFiles("nope.vert", "textured_mesh.frag"), Error);
}

TEST_F(ShaderProgramTest, MovedProgramKeepsItsId) {
  ShaderProgram a("a.vert", kVertex, "a.frag", kFragment);
  const unsigned int id = a.id();
  ShaderProgram b(std::move(a));
  EXPECT_EQ(b.id(), id);
  EXPECT_EQ(glIsProgram(id), GL_TRUE);
}
