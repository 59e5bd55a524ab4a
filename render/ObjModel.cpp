// OBJ loading (tinyobjloader, triangulated) and lit drawing with lit_mesh.*.
#include "render/ObjModel.hpp"

#include <glad/gl.h>
#include <tiny_obj_loader.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <string>

#include "engine/core/Error.hpp"
#include "render/CameraProjection.hpp"
#include "render/PixelCanvas.hpp"
#include "render/gl/ShaderProgram.hpp"

namespace reftrack::render {

namespace {

const Eigen::Vector3f kDefaultDiffuse(0.7f, 0.7f, 0.7f);

std::string firstLine(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

LitMesh loadObjMesh(const std::filesystem::path& file) {
  const std::string name = "OBJ file '" + file.string() + "'";
  if (!std::filesystem::is_regular_file(file)) throw Error(name + " does not exist");
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = file.parent_path().string();
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(file.string(), config))
    throw Error(name + " could not be parsed: " + firstLine(reader.Error()));
  const tinyobj::attrib_t& attrib = reader.GetAttrib();
  const auto& materials = reader.GetMaterials();
  const size_t vertexCount = attrib.vertices.size() / 3, normalCount = attrib.normals.size() / 3;

  LitMesh mesh;
  for (const tinyobj::shape_t& shape : reader.GetShapes()) {
    const auto& indices = shape.mesh.indices;
    size_t offset = 0;
    for (size_t face = 0; face < shape.mesh.num_face_vertices.size(); ++face) {
      const size_t corners = shape.mesh.num_face_vertices[face];
      if (corners != 3) {  // lines or points survive triangulation; they are not surfaces
        offset += corners;
        continue;
      }
      Eigen::Vector3f p[3], n[3];
      bool hasNormals = true;
      for (size_t k = 0; k < 3; ++k) {
        const tinyobj::index_t index = indices[offset + k];
        if (index.vertex_index < 0 || static_cast<size_t>(index.vertex_index) >= vertexCount)
          throw Error(name + ": face " + std::to_string(face + 1) + " of '" + shape.name +
                      "' refers to a vertex that does not exist");
        const size_t v = static_cast<size_t>(index.vertex_index);
        p[k] = {attrib.vertices[3 * v], attrib.vertices[3 * v + 1], attrib.vertices[3 * v + 2]};
        if (!p[k].allFinite()) throw Error(name + " has a non-finite vertex position");
        if (index.normal_index >= 0 && static_cast<size_t>(index.normal_index) < normalCount) {
          const size_t i = static_cast<size_t>(index.normal_index);
          n[k] = {attrib.normals[3 * i], attrib.normals[3 * i + 1], attrib.normals[3 * i + 2]};
          hasNormals = hasNormals && n[k].allFinite() && n[k].norm() > 0;
        } else {
          hasNormals = false;
        }
      }
      offset += 3;
      const Eigen::Vector3f faceNormal = (p[1] - p[0]).cross(p[2] - p[0]);
      if (!hasNormals) {
        if (!(faceNormal.norm() > 0)) continue;  // degenerate triangle, no surface to light
        n[0] = n[1] = n[2] = faceNormal.normalized();
      }
      const int material =
          face < shape.mesh.material_ids.size() ? shape.mesh.material_ids[face] : -1;
      Eigen::Vector3f diffuse = kDefaultDiffuse;
      if (material >= 0 && static_cast<size_t>(material) < materials.size()) {
        const auto& kd = materials[static_cast<size_t>(material)].diffuse;
        diffuse = {kd[0], kd[1], kd[2]};
      }
      for (size_t k = 0; k < 3; ++k) {
        mesh.positions.push_back(p[k]);
        mesh.normals.push_back(n[k].normalized());
        mesh.diffuse.push_back(diffuse);
      }
    }
  }
  if (mesh.positions.empty()) throw Error(name + " contains no triangles");
  return mesh;
}

Eigen::Matrix4d ModelTransform::modelToWorld() const {
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = scale * rotation;
  T.topRightCorner<3, 1>() = offset;
  return T;
}

void ModelTransform::check() const {
  if (!std::isfinite(scale) || !(scale > 0)) throw Error("model transform: scale must be positive");
  if (!rotation.allFinite() || !(rotation.transpose() * rotation).isIdentity(1e-6) ||
      !(rotation.determinant() > 0))
    throw Error("model transform: rotation must be a rotation matrix");
  if (!offset.allFinite()) throw Error("model transform: offset has a non-finite entry");
}

void ObjDrawOptions::check() const {
  transform.check();
  if (!lightDirectionCamera.allFinite() || !(lightDirectionCamera.norm() > 0))
    throw Error("model drawing: lightDirectionCamera must be a finite non-zero vector");
  if (!(ambient >= 0 && ambient <= 1)) throw Error("model drawing: ambient must be in [0, 1]");
}

struct ObjModel::Impl {
  ShaderProgram program = ShaderProgram::fromFiles("lit_mesh.vert", "lit_mesh.frag");
  GLuint vertexArray = 0, buffers[3] = {0, 0, 0};
  GLsizei vertexCount = 0;

  explicit Impl(const LitMesh& mesh) {
    if (mesh.positions.empty() || mesh.positions.size() % 3 != 0 ||
        mesh.normals.size() != mesh.positions.size() ||
        mesh.diffuse.size() != mesh.positions.size())
      throw Error("lit mesh needs 3 corners per triangle and one normal and colour per corner");
    glGenVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    glGenBuffers(3, buffers);
    const std::vector<Eigen::Vector3f>* attributes[3] = {&mesh.positions, &mesh.normals,
                                                         &mesh.diffuse};
    for (GLuint i = 0; i < 3; ++i) {
      glBindBuffer(GL_ARRAY_BUFFER, buffers[i]);
      glBufferData(GL_ARRAY_BUFFER,
                   static_cast<GLsizeiptr>(attributes[i]->size() * sizeof(Eigen::Vector3f)),
                   attributes[i]->data(), GL_STATIC_DRAW);
      glVertexAttribPointer(i, 3, GL_FLOAT, GL_FALSE, sizeof(Eigen::Vector3f), nullptr);
      glEnableVertexAttribArray(i);
    }
    glBindVertexArray(0);
    vertexCount = static_cast<GLsizei>(mesh.positions.size());
  }
  ~Impl() {
    glDeleteBuffers(3, buffers);
    glDeleteVertexArrays(1, &vertexArray);
  }
};

ObjModel::ObjModel(const std::filesystem::path& file)
    : impl_(std::make_unique<Impl>(loadObjMesh(file))) {}
ObjModel::ObjModel(const LitMesh& mesh) : impl_(std::make_unique<Impl>(mesh)) {}
ObjModel::~ObjModel() = default;

std::size_t ObjModel::triangleCount() const {
  return static_cast<std::size_t>(impl_->vertexCount / 3);
}

namespace {

// The lens of lit_mesh.vert: off without distortion (then the pinhole projection alone).
void setLensUniforms(const ShaderProgram& program, const PinholeView& view) {
  std::vector<double> d = view.distortion;
  const bool distort = std::any_of(d.begin(), d.end(), [](double c) { return c != 0.0; });
  program.set("u_distort", distort ? 1 : 0);
  if (!distort) return;
  if (d.size() != 4 && d.size() != 5 && d.size() != 8)
    throw Error("OBJ model: lens distortion must have 4, 5 or 8 coefficients, got " +
                std::to_string(d.size()));
  d.resize(8, 0.0);
  program.set("u_worldToCamera", Eigen::Matrix4f(view.worldToCamera.cast<float>()));
  program.set("u_focalCentre",
              Eigen::Vector4f(static_cast<float>(view.K(0, 0)), static_cast<float>(view.K(1, 1)),
                              static_cast<float>(view.K(0, 2)), static_cast<float>(view.K(1, 2))));
  program.set("u_skew", static_cast<float>(view.K(0, 1)));
  program.set("u_imageSize", Eigen::Vector2f(static_cast<float>(view.imageSize.width),
                                             static_cast<float>(view.imageSize.height)));
  program.set("u_distortionA", Eigen::Vector4f(static_cast<float>(d[0]), static_cast<float>(d[1]),
                                               static_cast<float>(d[2]), static_cast<float>(d[3])));
  program.set("u_distortionB", Eigen::Vector4f(static_cast<float>(d[4]), static_cast<float>(d[5]),
                                               static_cast<float>(d[6]), static_cast<float>(d[7])));
}

}  // namespace

void ObjModel::draw(const PinholeView& view, const ObjDrawOptions& options) {
  options.check();
  const Eigen::Matrix4d model = options.transform.modelToWorld();
  const Eigen::Matrix4d viewProjection =
      glViewProjection(view.K, view.imageSize, view.worldToCamera, view.nearPlane, view.farPlane);
  const Eigen::Matrix3d normalMatrix = model.topLeftCorner<3, 3>().inverse().transpose();
  const Eigen::Vector3d lightWorld = view.worldToCamera.topLeftCorner<3, 3>().transpose() *
                                     options.lightDirectionCamera.normalized();
  const ShaderProgram& program = impl_->program;
  program.use();
  program.set("u_viewProjection", Eigen::Matrix4f(viewProjection.cast<float>()));
  program.set("u_model", Eigen::Matrix4f(model.cast<float>()));
  program.set("u_normalMatrix", Eigen::Matrix3f(normalMatrix.cast<float>()));
  program.set("u_lightDirection", Eigen::Vector3f(lightWorld.cast<float>()));
  program.set("u_ambient", static_cast<float>(options.ambient));
  program.set("u_flatColour", Eigen::Vector4f(0, 0, 0, 0));
  setLensUniforms(program, view);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(impl_->vertexArray);
  // Push the filled surfaces back a little so the wireframe on them passes the depth test.
  glEnable(GL_POLYGON_OFFSET_FILL);
  glPolygonOffset(1.0f, 1.0f);
  glDrawArrays(GL_TRIANGLES, 0, impl_->vertexCount);
  glDisable(GL_POLYGON_OFFSET_FILL);
  if (options.wireframe) {
    program.set("u_flatColour", rgbaFromBgr(options.wireframeColourBgr));
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawArrays(GL_TRIANGLES, 0, impl_->vertexCount);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  glBindVertexArray(0);
}

}  // namespace reftrack::render
