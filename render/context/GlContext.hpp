#pragma once
// GlContext: one small interface over the ways reftrack gets an OpenGL 3.3 core context — a GLFW
// window, an OSMesa off-screen context, or an EGL surfaceless one. Render code only needs a
// current context; tracking code never sees which one runs.
#include <memory>
#include <string>
#include <utility>

#include "render/gl/GlLoader.hpp"

namespace reftrack::render {

class GlContext {
 public:
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;
  virtual ~GlContext() = default;
  virtual void makeCurrent() = 0;
  // "osmesa", "egl-surfaceless" or "glfw-window".
  const std::string& backendName() const { return backendName_; }
  // GL_VERSION / GL_RENDERER of the context, known after creation.
  const std::string& description() const { return description_; }

 protected:
  explicit GlContext(std::string backendName) : backendName_(std::move(backendName)) {}
  // For the implementation's constructor, once its context exists: makes it current (loading
  // the GL functions) and records its description.
  void makeCurrentAndDescribe() {
    makeCurrent();
    description_ = currentGlDescription();
  }

 private:
  std::string backendName_;
  std::string description_;
};

enum class HeadlessBackend { Auto, OsMesa, EglSurfaceless };

// Creates a current off-screen GL 3.3 core context with the GL functions loaded. Auto tries
// OSMesa, then EGL surfaceless; the environment variable REFTRACK_HEADLESS_GL=osmesa|egl forces
// one. Throws reftrack::Error explaining what is missing when none can be made.
std::unique_ptr<GlContext> createHeadlessContext(HeadlessBackend backend = HeadlessBackend::Auto);

}  // namespace reftrack::render
