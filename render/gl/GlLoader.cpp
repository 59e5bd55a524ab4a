// Fills glad's process-global GL function table from a context's get-proc-address function.
#include "render/gl/GlLoader.hpp"

#include <glad/gl.h>

#include "engine/core/Error.hpp"

namespace reftrack::render {

namespace {

GlProcLoader loadedThrough = nullptr;

std::string glString(GLenum name) {
  const auto* s = reinterpret_cast<const char*>(glGetString(name));
  return s ? s : "unknown";
}

}  // namespace

std::string loadGlFunctions(GlProcLoader loader) {
  loadedThrough = nullptr;
  const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
  if (version == 0) throw Error("could not load OpenGL functions for the current context");
  if (GLAD_VERSION_MAJOR(version) < 3 ||
      (GLAD_VERSION_MAJOR(version) == 3 && GLAD_VERSION_MINOR(version) < 3))
    throw Error("OpenGL 3.3 core is required, the context offers " +
                std::to_string(GLAD_VERSION_MAJOR(version)) + "." +
                std::to_string(GLAD_VERSION_MINOR(version)));
  loadedThrough = loader;
  return glString(GL_VERSION);
}

void loadGlFunctionsFor(GlProcLoader loader) {
  if (loader != loadedThrough) loadGlFunctions(loader);
}

std::string currentGlDescription() { return glString(GL_VERSION) + " | " + glString(GL_RENDERER); }

}  // namespace reftrack::render
