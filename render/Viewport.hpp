#pragma once
// Viewport: a rectangle of the framebuffer in GL window coordinates (origin bottom-left).
// fitImage letterboxes an image into a framebuffer; the video background and the 3-D overlay
// then share that viewport, so they stay registered.
#include <opencv2/core.hpp>

namespace reftrack::render {

struct Viewport {
  int x = 0, y = 0, width = 0, height = 0;
  bool operator==(const Viewport&) const = default;
};

// The largest rectangle of the image's aspect ratio centred in the framebuffer. Throws
// reftrack::Error for an empty image or framebuffer size.
Viewport fitImage(cv::Size imageSize, cv::Size framebufferSize);

// glViewport for `viewport`; currentViewport reads it back.
void applyViewport(const Viewport& viewport);
Viewport currentViewport();

}  // namespace reftrack::render
