#pragma once
// Loads the glad-generated GL 3.3 core entry points through the current context's
// get-proc-address function (GLFW, OSMesa or EGL). Throws reftrack::Error on failure.
#include <string>

namespace reftrack::render {

using GlProcLoader = void (*(*)(const char*))();

// Returns the GL version string of the context now current.
std::string loadGlFunctions(GlProcLoader loader);

}  // namespace reftrack::render
