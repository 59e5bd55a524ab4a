#include <gtest/gtest.h>

#include <cstdlib>

#include "engine/core/Error.hpp"
#include "render/context/ContextTestSupport.hpp"
#include "render/context/GlContext.hpp"

using namespace reftrack::render;

namespace {

// Sets an environment variable for one scope and restores the previous value.
class ScopedEnvironment {
 public:
  ScopedEnvironment(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    setenv(name, value, 1);
  }
  ~ScopedEnvironment() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }

 private:
  const char* name_;
  std::optional<std::string> old_;
};

}  // namespace

TEST(HeadlessContext, AutoPrefersOsMesa) {
  ScopedEnvironment env("REFTRACK_HEADLESS_GL", "");
  const auto context = createHeadlessContext();
  EXPECT_EQ(context->backendName(), "osmesa");
  EXPECT_EQ(reftrack::test::clearAndReadBack(1, 2, 3)[2], 3);
}

TEST(HeadlessContext, EnvironmentSelectsBackend) {
  {
    ScopedEnvironment env("REFTRACK_HEADLESS_GL", "osmesa");
    EXPECT_EQ(createHeadlessContext()->backendName(), "osmesa");
  }
  ScopedEnvironment env("REFTRACK_HEADLESS_GL", "egl");
  try {
    const auto context = createHeadlessContext();
    EXPECT_EQ(context->backendName(), "egl-surfaceless");
    EXPECT_EQ(reftrack::test::clearAndReadBack(7, 8, 9)[0], 7);
  } catch (const reftrack::Error& e) {
    GTEST_SKIP() << "EGL surfaceless unavailable on this machine: " << e.what();
  }
}

TEST(HeadlessContext, UnknownEnvironmentValueIsAClearError) {
  ScopedEnvironment env("REFTRACK_HEADLESS_GL", "vulkan");
  try {
    createHeadlessContext();
    FAIL() << "expected an error";
  } catch (const reftrack::Error& e) {
    EXPECT_NE(std::string(e.what()).find("REFTRACK_HEADLESS_GL='vulkan'"), std::string::npos);
  }
}
