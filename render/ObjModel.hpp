#pragma once
// ObjModel: a Wavefront OBJ model (tinyobjloader) drawn with simple lighting — two-sided Lambert
// plus ambient, times the material's diffuse colour (Kd; grey without a material) — and an
// optional wireframe overlay. Missing normals are replaced by flat face normals. The model
// transform is scale, rotation and offset: X_world = offset + scale * rotation * X_model.
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "render/SceneRenderer.hpp"

namespace reftrack::render {

// Triangles with per-corner attributes (three consecutive entries per triangle).
struct LitMesh {
  std::vector<Eigen::Vector3f> positions, normals, diffuse;  // diffuse RGB in 0..1
};

// Reads an OBJ (and its .mtl files beside it). Throws reftrack::Error naming the file: missing,
// unparsable, out-of-range indices, non-finite numbers, or no triangles.
LitMesh loadObjMesh(const std::filesystem::path& file);

struct ModelTransform {
  double scale = 1.0;
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();
  Eigen::Matrix4d modelToWorld() const;
  void check() const;  // throws reftrack::Error naming the bad field
};

struct ObjDrawOptions {
  ModelTransform transform;
  // Direction towards the light in the camera frame (OpenCV axes); default: from above-left
  // of the camera.
  Eigen::Vector3d lightDirectionCamera = Eigen::Vector3d(-0.3, -0.5, -1.0);
  double ambient = 0.3;  // 0..1
  bool wireframe = false;
  cv::Scalar wireframeColourBgr{20, 20, 20};
  void check() const;  // throws reftrack::Error naming the bad field
};

class ObjModel {
 public:
  // Loads and uploads; needs a current GL 3.3 context.
  explicit ObjModel(const std::filesystem::path& file);
  explicit ObjModel(const LitMesh& mesh);
  ~ObjModel();
  ObjModel(const ObjModel&) = delete;
  ObjModel& operator=(const ObjModel&) = delete;

  // Draws with depth testing into the current framebuffer and viewport (the caller clears depth).
  void draw(const PinholeView& view, const ObjDrawOptions& options = {});
  std::size_t triangleCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::render
