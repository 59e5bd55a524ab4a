#pragma once
// GlContext: one small interface over the ways reftrack gets an OpenGL 3.3 core context — a GLFW
// window, an OSMesa off-screen context, or an EGL surfaceless one. Render code only needs a
// current context; tracking code never sees which one runs.
#include <memory>
#include <string>

#include "render/gl/GlLoader.hpp"

namespace reftrack::render {

class GlContext {
 public:
  virtual ~GlContext() = default;
  virtual void makeCurrent() = 0;
  // "osmesa", "egl-surfaceless" or "glfw-window".
  virtual std::string backendName() const = 0;
  // GL_VERSION / GL_RENDERER of the context, known after creation.
  virtual std::string description() const = 0;
};

enum class HeadlessBackend { Auto, OsMesa, EglSurfaceless };

// Creates a current off-screen GL 3.3 core context with the GL functions loaded. Auto tries
// OSMesa, then EGL surfaceless; the environment variable REFTRACK_HEADLESS_GL=osmesa|egl forces
// one. Throws reftrack::Error explaining what is missing when none can be made.
std::unique_ptr<GlContext> createHeadlessContext(HeadlessBackend backend = HeadlessBackend::Auto);

}  // namespace reftrack::render
