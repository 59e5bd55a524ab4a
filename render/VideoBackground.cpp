// Video background: one full-viewport triangle sampling the frame texture.
#include "render/VideoBackground.hpp"

#include <glad/gl.h>

#include "render/Viewport.hpp"
#include "render/gl/ShaderProgram.hpp"
#include "render/gl/Texture2D.hpp"

namespace reftrack::render {

struct VideoBackground::Impl {
  ShaderProgram program =
      ShaderProgram::fromFiles("video_background.vert", "video_background.frag");
  Texture2D texture;
  GLuint emptyVertexArray = 0;  // core profile needs a bound VAO even without attributes
  Impl() { glGenVertexArrays(1, &emptyVertexArray); }
  ~Impl() { glDeleteVertexArrays(1, &emptyVertexArray); }
};

VideoBackground::VideoBackground() : impl_(std::make_unique<Impl>()) {}
VideoBackground::~VideoBackground() = default;

void VideoBackground::draw(const cv::Mat& image) {
  impl_->texture.upload(image, false);
  const Viewport viewport = currentViewport();
  impl_->texture.setNearestFiltering(viewport.width == image.cols && viewport.height == image.rows);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  impl_->program.use();
  impl_->program.set("u_image", 0);
  impl_->texture.bind(0);
  glBindVertexArray(impl_->emptyVertexArray);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
}

}  // namespace reftrack::render
