// createHeadlessContext: picks OSMesa or EGL surfaceless (Auto tries OSMesa first), or the one
// named by REFTRACK_HEADLESS_GL=osmesa|egl.
#include <cstdlib>
#include <string>

#include "engine/core/Error.hpp"
#include "render/context/EglSurfacelessContext.hpp"
#include "render/context/GlContext.hpp"
#include "render/context/OsMesaContext.hpp"

namespace reftrack::render {

namespace {

HeadlessBackend backendFromEnvironment(HeadlessBackend requested) {
  if (requested != HeadlessBackend::Auto) return requested;
  const char* value = std::getenv("REFTRACK_HEADLESS_GL");
  if (!value || !*value) return HeadlessBackend::Auto;
  const std::string name = value;
  if (name == "osmesa") return HeadlessBackend::OsMesa;
  if (name == "egl") return HeadlessBackend::EglSurfaceless;
  if (name == "auto") return HeadlessBackend::Auto;
  throw Error("REFTRACK_HEADLESS_GL='" + name + "' is not one of osmesa, egl, auto");
}

}  // namespace

std::unique_ptr<GlContext> createHeadlessContext(HeadlessBackend backend) {
  switch (backendFromEnvironment(backend)) {
    case HeadlessBackend::OsMesa:
      return std::make_unique<OsMesaContext>();
    case HeadlessBackend::EglSurfaceless:
      return std::make_unique<EglSurfacelessContext>();
    case HeadlessBackend::Auto:
      break;
  }
  std::string osmesaFailure;
  try {
    return std::make_unique<OsMesaContext>();
  } catch (const Error& e) {
    osmesaFailure = e.what();
  }
  try {
    return std::make_unique<EglSurfacelessContext>();
  } catch (const Error& e) {
    throw Error("no headless OpenGL 3.3 context: OSMesa: " + osmesaFailure + "; EGL: " + e.what());
  }
}

}  // namespace reftrack::render
