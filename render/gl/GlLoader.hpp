#pragma once
// Loads the glad-generated GL 3.3 core entry points through the current context's
// get-proc-address function (GLFW, OSMesa or EGL). Throws reftrack::Error on failure.
// glad's function table is process-global: contexts call loadGlFunctionsFor() on makeCurrent so
// the table always matches the loader of the context that is current.
#include <string>

namespace reftrack::render {

using GlProcLoader = void (*(*)(const char*))();

// Loads every entry point through `loader`; returns the GL version string of the context now
// current. Throws reftrack::Error if loading fails or the context is older than 3.3.
std::string loadGlFunctions(GlProcLoader loader);

// Reloads only when the table was last filled through a different loader.
void loadGlFunctionsFor(GlProcLoader loader);

// "GL_VERSION | GL_RENDERER" of the current context.
std::string currentGlDescription();

}  // namespace reftrack::render
