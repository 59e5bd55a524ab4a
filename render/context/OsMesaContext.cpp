// OSMesa context: core profile 3.3 requested through OSMesaCreateContextAttribs, bound to a
// 16x16 RGBA client buffer (drawing goes to FBOs).
#include "render/context/OsMesaContext.hpp"

#include <GL/osmesa.h>

#include <array>
#include <vector>

#include "engine/core/Error.hpp"
#include "render/gl/GlLoader.hpp"

namespace reftrack::render {

namespace {
constexpr int kBufferSide = 16;
GlProcLoader osmesaLoader() { return reinterpret_cast<GlProcLoader>(&OSMesaGetProcAddress); }
}  // namespace

struct OsMesaContext::Impl {
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer = std::vector<unsigned char>(kBufferSide * kBufferSide * 4);
};

OsMesaContext::OsMesaContext() : GlContext("osmesa"), impl_(std::make_unique<Impl>()) {
  const std::array<int, 13> attributes = {OSMESA_FORMAT,
                                          OSMESA_RGBA,
                                          OSMESA_DEPTH_BITS,
                                          24,
                                          OSMESA_PROFILE,
                                          OSMESA_CORE_PROFILE,
                                          OSMESA_CONTEXT_MAJOR_VERSION,
                                          3,
                                          OSMESA_CONTEXT_MINOR_VERSION,
                                          3,
                                          0,
                                          0,
                                          0};
  impl_->context = OSMesaCreateContextAttribs(attributes.data(), nullptr);
  if (!impl_->context)
    throw Error(
        "OSMesa could not create an OpenGL 3.3 core context (libosmesa6 missing or too old)");
  try {
    makeCurrentAndDescribe();
  } catch (...) {
    OSMesaDestroyContext(impl_->context);
    throw;
  }
}

OsMesaContext::~OsMesaContext() {
  if (OSMesaGetCurrentContext() == impl_->context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(impl_->context);
}

void OsMesaContext::makeCurrent() {
  if (!OSMesaMakeCurrent(impl_->context, impl_->buffer.data(), GL_UNSIGNED_BYTE, kBufferSide,
                         kBufferSide))
    throw Error("OSMesa could not make its context current");
  loadGlFunctionsFor(osmesaLoader());
}

}  // namespace reftrack::render
