#pragma once
// SceneRenderer: draws textured triangle meshes with a pinhole camera into an off-screen
// target and reads the result back. Camera: K (3x3) and a world->camera pose in OpenCV axes
// (x right, y down, z forward). A world point X lands exactly at pixel K(RX+t), with pixel
// centres at integer coordinates (OpenCV convention). Needs a current GL 3.3 context.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

namespace reftrack::render {

struct TexturedMesh {
  std::vector<Eigen::Vector3f> positions;  // world coordinates (metres)
  std::vector<Eigen::Vector2f> uvs;  // texture coordinates in [0,1], (0,0) = top-left of `texture`
  std::vector<std::uint32_t> indices;  // triangles
  cv::Mat texture;                     // CV_8UC3 (BGR) or CV_8UC1
};

struct PinholeView {
  Eigen::Matrix3d K = Eigen::Matrix3d::Identity();
  cv::Size imageSize{0, 0};
  Eigen::Matrix4d worldToCamera = Eigen::Matrix4d::Identity();  // OpenCV axes
  double nearPlane = 0.01, farPlane = 100.0;                    // metres
  // OpenCV lens distortion k1,k2,p1,p2[,k3[,k4,k5,k6]] (empty: an ideal pinhole). The overlays
  // drawn in pixel space (WireframeCube, PointMarkers) bend through it exactly; meshes distort
  // per vertex (see SceneRenderer::draw).
  std::vector<double> distortion;
};

// Holds uploaded meshes (GPU textures and buffers) and draws them.
class SceneRenderer {
 public:
  SceneRenderer();  // needs a current GL 3.3 context with the functions loaded
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Uploads a mesh (throws reftrack::Error on inconsistent sizes or an empty texture).
  void addMesh(const TexturedMesh& mesh);
  void clearMeshes();

  // Renders all meshes off-screen and returns the BGR image (CV_8UC3) of view.imageSize. With
  // supersample s > 1 it renders at s times the size with K scaled about pixel centres and
  // area-averages back down, so the pixel-centre convention above still holds exactly. When
  // `depthMetres` is given it receives the camera-frame depth z per pixel (CV_32F, 0 where empty)
  // at view.imageSize.
  cv::Mat render(const PinholeView& view, int supersample = 1, cv::Mat* depthMetres = nullptr,
                 const cv::Scalar& clearColourBgr = cv::Scalar(0, 0, 0));

  // Draws into the framebuffer and viewport currently bound (for compositing in the viewer).
  void draw(const PinholeView& view);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reftrack::render
