// FBO with renderbuffers; glReadPixels returns rows bottom-up, so read-backs are flipped.
#include "render/RenderTarget.hpp"

#include <glad/gl.h>

#include <opencv2/core.hpp>
#include <string>

#include "engine/core/Error.hpp"
#include "render/CameraProjection.hpp"

namespace reftrack::render {

RenderTarget::RenderTarget(cv::Size size) : size_(size) {
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
  if (size.width <= 0 || size.height <= 0 || size.width > maxSize || size.height > maxSize)
    throw Error("render target size " + std::to_string(size.width) + "x" +
                std::to_string(size.height) + " must be positive and at most " +
                std::to_string(maxSize) + " per side");
  glGenFramebuffers(1, &framebuffer_);
  glGenRenderbuffers(1, &colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, size.width, size.height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, size.width, size.height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  GLint previous = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previous);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous));
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteRenderbuffers(1, &colour_);
    glDeleteRenderbuffers(1, &depth_);
    glDeleteFramebuffers(1, &framebuffer_);
    throw Error("render target framebuffer incomplete (status " + std::to_string(status) + ")");
  }
}

RenderTarget::~RenderTarget() {
  glDeleteRenderbuffers(1, &colour_);
  glDeleteRenderbuffers(1, &depth_);
  glDeleteFramebuffers(1, &framebuffer_);
}

void RenderTarget::bind() const {
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
  glViewport(0, 0, size_.width, size_.height);
}

cv::Mat RenderTarget::readColourBgr() const {
  cv::Mat bottomUp(size_, CV_8UC3);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glReadPixels(0, 0, size_.width, size_.height, GL_BGR, GL_UNSIGNED_BYTE, bottomUp.data);
  cv::Mat image;
  cv::flip(bottomUp, image, 0);
  return image;
}

cv::Mat RenderTarget::readDepthMetres(double nearPlane, double farPlane) const {
  if (!(nearPlane > 0) || !(farPlane > nearPlane))
    throw Error("depth read-back needs 0 < near < far");
  cv::Mat bottomUp(size_, CV_32F);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glPixelStorei(GL_PACK_ROW_LENGTH, 0);
  glReadPixels(0, 0, size_.width, size_.height, GL_DEPTH_COMPONENT, GL_FLOAT, bottomUp.data);
  cv::Mat depth(size_, CV_32F);
  for (int row = 0; row < size_.height; ++row) {
    const float* in = bottomUp.ptr<float>(size_.height - 1 - row);
    float* out = depth.ptr<float>(row);
    for (int col = 0; col < size_.width; ++col)
      out[col] = static_cast<float>(depthBufferToMetres(in[col], nearPlane, farPlane));
  }
  return depth;
}

}  // namespace reftrack::render
