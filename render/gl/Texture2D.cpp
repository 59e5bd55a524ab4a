// Texture upload from OpenCV images: BGR through GL_BGR, grey through GL_RED with an RGB swizzle.
#include "render/gl/Texture2D.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

#include "engine/core/Error.hpp"

namespace reftrack::render {

namespace {

// GL_EXT/ARB_texture_filter_anisotropic (core in 4.6; not in glad's 3.3 core header).
constexpr GLenum kTextureMaxAnisotropy = 0x84FE;
constexpr GLenum kMaxTextureMaxAnisotropy = 0x84FF;

float maxAnisotropy() {
  GLint count = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const auto* name = reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i));
    if (name && (std::strcmp(name, "GL_EXT_texture_filter_anisotropic") == 0 ||
                 std::strcmp(name, "GL_ARB_texture_filter_anisotropic") == 0)) {
      GLfloat value = 1.0f;
      glGetFloatv(kMaxTextureMaxAnisotropy, &value);
      return value;
    }
  }
  return 1.0f;
}

}  // namespace

Texture2D::Texture2D() { glGenTextures(1, &texture_); }

Texture2D::~Texture2D() {
  if (texture_) glDeleteTextures(1, &texture_);
}

Texture2D::Texture2D(Texture2D&& other) noexcept
    : texture_(std::exchange(other.texture_, 0)),
      size_(other.size_),
      type_(other.type_),
      mipmapped_(other.mipmapped_) {}

Texture2D& Texture2D::operator=(Texture2D&& other) noexcept {
  if (this != &other) {
    if (texture_) glDeleteTextures(1, &texture_);
    texture_ = std::exchange(other.texture_, 0);
    size_ = other.size_;
    type_ = other.type_;
    mipmapped_ = other.mipmapped_;
  }
  return *this;
}

void Texture2D::upload(const cv::Mat& input, bool mipmapped) {
  if (input.empty()) throw Error("texture image is empty");
  // GL_UNPACK_ROW_LENGTH counts whole pixels, so rows padded by a fraction of a pixel are copied.
  const cv::Mat image = input.step[0] % input.elemSize() == 0 ? input : input.clone();
  if (image.type() != CV_8UC3 && image.type() != CV_8UC1)
    throw Error("texture image must be CV_8UC3 (BGR) or CV_8UC1 (grey), got type " +
                std::to_string(image.type()));
  GLint maxSize = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
  if (image.cols > maxSize || image.rows > maxSize)
    throw Error("texture image " + std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                " exceeds GL_MAX_TEXTURE_SIZE " + std::to_string(maxSize));
  const bool grey = image.channels() == 1;
  const GLenum format = grey ? GL_RED : GL_BGR;
  glBindTexture(GL_TEXTURE_2D, texture_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, static_cast<GLint>(image.step[0] / image.elemSize()));
  if (image.size() == size_ && image.type() == type_ && mipmapped == mipmapped_) {
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, image.cols, image.rows, format, GL_UNSIGNED_BYTE,
                    image.data);
  } else {
    glTexImage2D(GL_TEXTURE_2D, 0, grey ? GL_R8 : GL_RGB8, image.cols, image.rows, 0, format,
                 GL_UNSIGNED_BYTE, image.data);
    const GLint swizzleGrey[4] = {GL_RED, GL_RED, GL_RED, GL_ONE};
    const GLint swizzleColour[4] = {GL_RED, GL_GREEN, GL_BLUE, GL_ONE};
    glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, grey ? swizzleGrey : swizzleColour);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    if (mipmapped) {
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
      const float anisotropy = std::min(maxAnisotropy(), 16.0f);
      if (anisotropy > 1.0f) glTexParameterf(GL_TEXTURE_2D, kTextureMaxAnisotropy, anisotropy);
    } else {
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    }
    size_ = image.size();
    type_ = image.type();
    mipmapped_ = mipmapped;
  }
  if (mipmapped) glGenerateMipmap(GL_TEXTURE_2D);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);
}

void Texture2D::setNearestFiltering(bool nearest) {
  if (mipmapped_) return;
  glBindTexture(GL_TEXTURE_2D, texture_);
  const GLint filter = nearest ? GL_NEAREST : GL_LINEAR;
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
}

void Texture2D::bind(int unit) const {
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  glBindTexture(GL_TEXTURE_2D, texture_);
}

}  // namespace reftrack::render
