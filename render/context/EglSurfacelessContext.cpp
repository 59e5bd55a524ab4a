// EGL surfaceless context: eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA), a desktop
// OpenGL 3.3 core context, made current without any surface (EGL_KHR_surfaceless_context).
#include "render/context/EglSurfacelessContext.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <sstream>
#include <string>

#include "engine/core/Error.hpp"
#include "render/gl/GlLoader.hpp"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace reftrack::render {

namespace {

GlProcLoader eglLoader() { return reinterpret_cast<GlProcLoader>(&eglGetProcAddress); }

bool hasExtension(const char* list, const std::string& name) {
  if (!list) return false;
  std::istringstream words(list);
  std::string word;
  while (words >> word)
    if (word == name) return true;
  return false;
}

std::string eglErrorText() {
  char code[16];
  std::snprintf(code, sizeof code, "0x%04X", static_cast<unsigned>(eglGetError()));
  return std::string("EGL error ") + code;
}

}  // namespace

struct EglSurfacelessContext::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  ~Impl() {
    if (display == EGL_NO_DISPLAY) return;
    if (context != EGL_NO_CONTEXT) {
      if (eglGetCurrentContext() == context)
        eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      eglDestroyContext(display, context);
    }
    eglTerminate(display);
  }
};

EglSurfacelessContext::EglSurfacelessContext()
    : GlContext("egl-surfaceless"), impl_(std::make_unique<Impl>()) {
  const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  for (const char* needed : {"EGL_EXT_platform_base", "EGL_MESA_platform_surfaceless"})
    if (!hasExtension(clientExtensions, needed))
      throw Error(std::string("EGL surfaceless platform unavailable: the EGL client lacks ") +
                  needed + " (install libegl-mesa0)");
  const auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (!getPlatformDisplay)
    throw Error("EGL surfaceless platform unavailable: no eglGetPlatformDisplayEXT");
  impl_->display = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  if (impl_->display == EGL_NO_DISPLAY)
    throw Error("EGL surfaceless platform unavailable: eglGetPlatformDisplayEXT failed (" +
                eglErrorText() + ")");
  EGLint major = 0, minor = 0;
  bool initialised = false;
  {
#if defined(__SANITIZE_ADDRESS__)
    // Mesa's DRI driver allocates a one-time state in eglInitialize (a pthread_once) that it never
    // frees; its module is gone by the leak report, so no suppression file can name it. Not
    // tracked for leaks; this call allocates nothing of ours.
    const __lsan::ScopedDisabler mesaOneTimeState;
#endif
    initialised = eglInitialize(impl_->display, &major, &minor);
  }
  if (!initialised) {
    impl_->display = EGL_NO_DISPLAY;
    throw Error("EGL surfaceless display could not be initialised (" + eglErrorText() + ")");
  }
  const char* displayExtensions = eglQueryString(impl_->display, EGL_EXTENSIONS);
  for (const char* needed : {"EGL_KHR_surfaceless_context", "EGL_KHR_create_context"})
    if (!hasExtension(displayExtensions, needed))
      throw Error(std::string("EGL surfaceless display lacks ") + needed);
  if (!eglBindAPI(EGL_OPENGL_API))
    throw Error("EGL cannot bind the desktop OpenGL API (" + eglErrorText() + ")");

  const EGLint configAttributes[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                     EGL_PBUFFER_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configCount = 0;
  const bool noConfig = hasExtension(displayExtensions, "EGL_KHR_no_config_context");
  if (!eglChooseConfig(impl_->display, configAttributes, &config, 1, &configCount) ||
      configCount < 1) {
    if (!noConfig) throw Error("EGL surfaceless display offers no desktop OpenGL config");
    config = nullptr;  // EGL_NO_CONFIG_KHR
  }
  const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                      3,
                                      EGL_CONTEXT_MINOR_VERSION,
                                      3,
                                      EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                      EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                      EGL_NONE};
  impl_->context = eglCreateContext(impl_->display, config, EGL_NO_CONTEXT, contextAttributes);
  if (impl_->context == EGL_NO_CONTEXT)
    throw Error("EGL could not create an OpenGL 3.3 core context (" + eglErrorText() + ")");
  makeCurrentAndDescribe();
}

EglSurfacelessContext::~EglSurfacelessContext() = default;

void EglSurfacelessContext::makeCurrent() {
  if (!eglMakeCurrent(impl_->display, EGL_NO_SURFACE, EGL_NO_SURFACE, impl_->context))
    throw Error("EGL could not make the surfaceless context current (" + eglErrorText() + ")");
  loadGlFunctionsFor(eglLoader());
}

}  // namespace reftrack::render
