#include "render/gl/GlLoader.hpp"

#include <glad/gl.h>

#include <stdexcept>

namespace reftrack::render {

std::string loadGlFunctions(GlProcLoader loader) {
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
  if (version == 0) throw std::runtime_error("could not load OpenGL functions for the current context");
  if (GLAD_VERSION_MAJOR(version) < 3 || (GLAD_VERSION_MAJOR(version) == 3 && GLAD_VERSION_MINOR(version) < 3))
    throw std::runtime_error("OpenGL 3.3 core is required, the context offers " +
                             std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                             std::to_string(GLAD_VERSION_MINOR(version)));
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return s ? s : "unknown";
}

}  // namespace reftrack::render
