#pragma once
// OsMesaContext: an off-screen OpenGL 3.3 core context from OSMesa (Mesa's software renderer).
// Its default framebuffer is a tiny client buffer; render into framebuffer objects
// (RenderTarget) instead.
#include <memory>
#include <string>

#include "render/context/GlContext.hpp"

namespace reftrack::render {

class OsMesaContext final : public GlContext {
 public:
  // Creates the context, makes it current and loads the GL functions. Throws reftrack::Error.
  OsMesaContext();
  ~OsMesaContext() override;

  void makeCurrent() override;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::render
