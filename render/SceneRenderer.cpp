// SceneRenderer: textured meshes drawn with the K-exact projection of CameraProjection.hpp.
#include "render/SceneRenderer.hpp"

#include <glad/gl.h>

#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "engine/core/Error.hpp"
#include "render/CameraProjection.hpp"
#include "render/RenderTarget.hpp"
#include "render/gl/ShaderProgram.hpp"
#include "render/gl/Texture2D.hpp"

namespace reftrack::render {

namespace {

void checkMesh(const TexturedMesh& mesh) {
  if (mesh.positions.empty()) throw Error("mesh has no vertex positions");
  if (mesh.uvs.size() != mesh.positions.size())
    throw Error("mesh has " + std::to_string(mesh.uvs.size()) + " uvs for " +
                std::to_string(mesh.positions.size()) + " positions");
  if (mesh.indices.empty() || mesh.indices.size() % 3 != 0)
    throw Error("mesh indices must be a non-empty multiple of 3, got " +
                std::to_string(mesh.indices.size()));
  for (std::uint32_t index : mesh.indices)
    if (index >= mesh.positions.size())
      throw Error("mesh index " + std::to_string(index) + " is out of range (" +
                  std::to_string(mesh.positions.size()) + " positions)");
  for (const Eigen::Vector3f& p : mesh.positions)
    if (!p.allFinite()) throw Error("mesh has a non-finite vertex position");
  for (const Eigen::Vector2f& uv : mesh.uvs)
    if (!uv.allFinite()) throw Error("mesh has a non-finite texture coordinate");
  if (mesh.texture.empty()) throw Error("mesh texture is empty");
  if (mesh.texture.type() != CV_8UC3 && mesh.texture.type() != CV_8UC1)
    throw Error("mesh texture must be CV_8UC3 (BGR) or CV_8UC1");
}

void checkView(const PinholeView& view) {
  // Throws naming K, size, near/far or the pose when one is invalid.
  glViewProjection(view.K, view.imageSize, view.worldToCamera, view.nearPlane, view.farPlane);
}

struct GpuMesh {
  GLuint vertexArray = 0, positionBuffer = 0, uvBuffer = 0, indexBuffer = 0;
  GLsizei indexCount = 0;
  Texture2D texture;

  explicit GpuMesh(const TexturedMesh& mesh) {
    glGenVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glGenBuffers(1, &positionBuffer);
    glBindBuffer(GL_ARRAY_BUFFER, positionBuffer);
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.positions.size() * sizeof(Eigen::Vector3f)),
                 mesh.positions.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
    glEnableVertexAttribArray(0);
    glGenBuffers(1, &uvBuffer);
    glBindBuffer(GL_ARRAY_BUFFER, uvBuffer);
    glBufferData(GL_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.uvs.size() * sizeof(Eigen::Vector2f)),
                 mesh.uvs.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector2f), nullptr);
    glEnableVertexAttribArray(1);
    glGenBuffers(1, &indexBuffer);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, indexBuffer);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER,
                 static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(std::uint32_t)),
                 mesh.indices.data(), GL_STATIC_DRAW);
    glBindVertexArray(0);
    indexCount = static_cast<GLsizei>(mesh.indices.size());
    texture.upload(mesh.texture, true);
  }
  ~GpuMesh() {
    glDeleteBuffers(1, &positionBuffer);
    glDeleteBuffers(1, &uvBuffer);
    glDeleteBuffers(1, &indexBuffer);
    glDeleteVertexArrays(1, &vertexArray);
  }
  GpuMesh(const GpuMesh&) = delete;
  GpuMesh& operator=(const GpuMesh&) = delete;
};

}  // namespace

struct SceneRenderer::Impl {
  ShaderProgram program = ShaderProgram::fromFiles("textured_mesh.vert", "textured_mesh.frag");
  std::vector<std::unique_ptr<GpuMesh>> meshes;
  std::optional<RenderTarget> target;  // reused while the render size stays the same

  RenderTarget& targetOfSize(cv::Size size) {
    if (!target || target->size() != size) {
      target.reset();
      target.emplace(size);
    }
    return *target;
  }

  void drawMeshes(const Eigen::Matrix3d& K, cv::Size imageSize, const PinholeView& view) {
    const Eigen::Matrix4f viewProjection =
        glViewProjection(K, imageSize, view.worldToCamera, view.nearPlane, view.farPlane)
            .cast<float>();
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    program.use();
    program.set("u_viewProjection", viewProjection);
    program.set("u_texture", 0);
    for (const auto& mesh : meshes) {
      mesh->texture.bind(0);
      glBindVertexArray(mesh->vertexArray);
      glDrawElements(GL_TRIANGLES, mesh->indexCount, GL_UNSIGNED_INT, nullptr);
    }
    glBindVertexArray(0);
  }
};

SceneRenderer::SceneRenderer() : impl_(std::make_unique<Impl>()) {}
SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::addMesh(const TexturedMesh& mesh) {
  checkMesh(mesh);
  impl_->meshes.push_back(std::make_unique<GpuMesh>(mesh));
}

void SceneRenderer::clearMeshes() { impl_->meshes.clear(); }

cv::Mat SceneRenderer::render(const PinholeView& view, int supersample, cv::Mat* depthMetres,
                              const cv::Scalar& clearColourBgr) {
  checkView(view);
  if (supersample < 1)
    throw Error("supersample factor must be >= 1, got " + std::to_string(supersample));
  const cv::Size renderSize(view.imageSize.width * supersample,
                            view.imageSize.height * supersample);
  RenderTarget& target = impl_->targetOfSize(renderSize);
  GLint previousFramebuffer = 0;
  glGetIntegerv(GL_FRAMEBUFFER_BINDING, &previousFramebuffer);
  target.bind();
  glClearColor(static_cast<float>(clearColourBgr[2] / 255.0),
               static_cast<float>(clearColourBgr[1] / 255.0),
               static_cast<float>(clearColourBgr[0] / 255.0), 1.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  impl_->drawMeshes(supersampledK(view.K, supersample), renderSize, view);

  cv::Mat colour = target.readColourBgr();
  if (supersample > 1) cv::resize(colour, colour, view.imageSize, 0, 0, cv::INTER_AREA);
  if (depthMetres) {
    const cv::Mat fullDepth = target.readDepthMetres(view.nearPlane, view.farPlane);
    if (supersample == 1) {
      *depthMetres = fullDepth;
    } else {
      // Depth is not averaged (that would invent depths across edges): each pixel takes the
      // sample nearest its centre, which for odd factors lies exactly on the centre.
      cv::Mat depth(view.imageSize, CV_32F);
      for (int row = 0; row < depth.rows; ++row)
        for (int col = 0; col < depth.cols; ++col)
          depth.at<float>(row, col) = fullDepth.at<float>(row * supersample + supersample / 2,
                                                          col * supersample + supersample / 2);
      *depthMetres = depth;
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previousFramebuffer));
  return colour;
}

void SceneRenderer::draw(const PinholeView& view) {
  checkView(view);
  impl_->drawMeshes(view.K, view.imageSize, view);
}

}  // namespace reftrack::render
