#pragma once
// EglSurfacelessContext: an off-screen OpenGL 3.3 core context on the EGL_MESA_platform_surfaceless
// display (no window system, no pbuffer): it is made current with EGL_NO_SURFACE and draws only
// into framebuffer objects (RenderTarget).
#include <memory>
#include <string>

#include "render/context/GlContext.hpp"

namespace reftrack::render {

class EglSurfacelessContext final : public GlContext {
 public:
  // Creates the context, makes it current and loads the GL functions. Throws reftrack::Error
  // naming the missing EGL extension or failing call when the platform is unavailable.
  EglSurfacelessContext();
  ~EglSurfacelessContext() override;

  void makeCurrent() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::render
