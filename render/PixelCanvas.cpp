// PixelCanvas: a growing vertex list streamed to one buffer and drawn with pixel_colour.*.
#include "render/PixelCanvas.hpp"

#include <glad/gl.h>

#include <cmath>

#include "engine/core/Error.hpp"
#include "render/gl/ShaderProgram.hpp"

namespace reftrack::render {

namespace {

struct ColouredVertex {
  float x, y;
  float r, g, b, a;
};

constexpr int kDiscSegments = 32;

}  // namespace

Eigen::Vector4f rgbaFromBgr(const cv::Scalar& colourBgr, double alpha) {
  return Eigen::Vector4f(static_cast<float>(colourBgr[2] / 255.0),
                         static_cast<float>(colourBgr[1] / 255.0),
                         static_cast<float>(colourBgr[0] / 255.0), static_cast<float>(alpha));
}

struct PixelCanvas::Impl {
  ShaderProgram program = ShaderProgram::fromFiles("pixel_colour.vert", "pixel_colour.frag");
  std::vector<ColouredVertex> vertices;
  GLuint vertexArray = 0, buffer = 0;

  Impl() {
    glGenVertexArrays(1, &vertexArray);
    glGenBuffers(1, &buffer);
    glBindVertexArray(vertexArray);
    glBindBuffer(GL_ARRAY_BUFFER, buffer);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(ColouredVertex), nullptr);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(ColouredVertex),
                          reinterpret_cast<const void*>(2 * sizeof(float)));
    glEnableVertexAttribArray(1);
    glBindVertexArray(0);
  }
  ~Impl() {
    glDeleteBuffers(1, &buffer);
    glDeleteVertexArrays(1, &vertexArray);
  }
  void push(const Eigen::Vector2f& p, const Eigen::Vector4f& c) {
    vertices.push_back({p.x(), p.y(), c[0], c[1], c[2], c[3]});
  }
};

PixelCanvas::PixelCanvas() : impl_(std::make_unique<Impl>()) {}
PixelCanvas::~PixelCanvas() = default;

void PixelCanvas::addTriangle(const Eigen::Vector2f& a, const Eigen::Vector2f& b,
                              const Eigen::Vector2f& c, const Eigen::Vector4f& rgba) {
  if (!a.allFinite() || !b.allFinite() || !c.allFinite() || !rgba.allFinite())
    throw Error("2-D overlay geometry has a non-finite coordinate or colour");
  impl_->push(a, rgba);
  impl_->push(b, rgba);
  impl_->push(c, rgba);
}

void PixelCanvas::addQuad(const Eigen::Vector2f& a, const Eigen::Vector2f& b,
                          const Eigen::Vector2f& c, const Eigen::Vector2f& d,
                          const Eigen::Vector4f& rgba) {
  addTriangle(a, b, c, rgba);
  addTriangle(a, c, d, rgba);
}

void PixelCanvas::addThickLine(const Eigen::Vector2f& from, const Eigen::Vector2f& to, float width,
                               const Eigen::Vector4f& rgba) {
  if (!(width > 0)) throw Error("line width must be positive");
  Eigen::Vector2f along = to - from;
  const float length = along.norm();
  along = length > 0 ? Eigen::Vector2f(along / length) : Eigen::Vector2f(1, 0);
  const Eigen::Vector2f halfAlong = along * (width / 2);
  const Eigen::Vector2f halfAcross = Eigen::Vector2f(-along.y(), along.x()) * (width / 2);
  const Eigen::Vector2f start = from - halfAlong, end = to + halfAlong;
  addQuad(start - halfAcross, end - halfAcross, end + halfAcross, start + halfAcross, rgba);
}

void PixelCanvas::addDisc(const Eigen::Vector2f& centre, float radius,
                          const Eigen::Vector4f& rgba) {
  if (!(radius > 0)) throw Error("dot radius must be positive");
  for (int i = 0; i < kDiscSegments; ++i) {
    const double a0 = 2 * M_PI * i / kDiscSegments, a1 = 2 * M_PI * (i + 1) / kDiscSegments;
    addTriangle(centre,
                centre + radius * Eigen::Vector2f(static_cast<float>(std::cos(a0)),
                                                  static_cast<float>(std::sin(a0))),
                centre + radius * Eigen::Vector2f(static_cast<float>(std::cos(a1)),
                                                  static_cast<float>(std::sin(a1))),
                rgba);
  }
}

bool PixelCanvas::empty() const { return impl_->vertices.empty(); }
void PixelCanvas::clear() { impl_->vertices.clear(); }

void PixelCanvas::draw(cv::Size imageSize) {
  if (imageSize.width <= 0 || imageSize.height <= 0)
    throw Error("2-D overlay image size must be positive");
  if (impl_->vertices.empty()) return;
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  impl_->program.use();
  impl_->program.set("u_imageSize", Eigen::Vector2f(static_cast<float>(imageSize.width),
                                                    static_cast<float>(imageSize.height)));
  glBindVertexArray(impl_->vertexArray);
  glBindBuffer(GL_ARRAY_BUFFER, impl_->buffer);
  glBufferData(GL_ARRAY_BUFFER,
               static_cast<GLsizeiptr>(impl_->vertices.size() * sizeof(ColouredVertex)),
               impl_->vertices.data(), GL_STREAM_DRAW);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(impl_->vertices.size()));
  glBindVertexArray(0);
  glDisable(GL_BLEND);
}

}  // namespace reftrack::render
