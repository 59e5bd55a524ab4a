// Lookup in the generated shader table.
#include "render/gl/EmbeddedShaders.hpp"

#include "engine/core/Error.hpp"

namespace reftrack::render {

std::string embeddedShaderSource(const std::string& fileName) {
  for (const EmbeddedShader& shader : embeddedShaders())
    if (fileName == shader.fileName) return shader.source;
  throw Error("shader 'shaders/" + fileName +
              "' is not embedded (add it to REFTRACK_SHADER_FILES in render/CMakeLists.txt)");
}

}  // namespace reftrack::render
