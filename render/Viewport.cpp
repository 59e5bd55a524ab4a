// Letterboxing arithmetic and the GL viewport calls.
#include "render/Viewport.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/Error.hpp"

namespace reftrack::render {

Viewport fitImage(cv::Size imageSize, cv::Size framebufferSize) {
  if (imageSize.width <= 0 || imageSize.height <= 0)
    throw Error("fitImage: image size must be positive");
  if (framebufferSize.width <= 0 || framebufferSize.height <= 0)
    throw Error("fitImage: framebuffer size must be positive");
  const double scale = std::min(static_cast<double>(framebufferSize.width) / imageSize.width,
                                static_cast<double>(framebufferSize.height) / imageSize.height);
  Viewport viewport;
  viewport.width =
      std::clamp(static_cast<int>(std::lround(imageSize.width * scale)), 1, framebufferSize.width);
  viewport.height = std::clamp(static_cast<int>(std::lround(imageSize.height * scale)), 1,
                               framebufferSize.height);
  viewport.x = (framebufferSize.width - viewport.width) / 2;
  viewport.y = (framebufferSize.height - viewport.height) / 2;
  return viewport;
}

void applyViewport(const Viewport& viewport) {
  glViewport(viewport.x, viewport.y, viewport.width, viewport.height);
}

Viewport currentViewport() {
  GLint v[4] = {0, 0, 0, 0};
  glGetIntegerv(GL_VIEWPORT, v);
  return {v[0], v[1], v[2], v[3]};
}

}  // namespace reftrack::render
