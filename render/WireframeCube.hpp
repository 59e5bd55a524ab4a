#pragma once
// WireframeCube: the classic AR test object — a cube's 12 edges as thick lines (screen-space
// quads, since core profile GL ignores glLineWidth > 1) and optionally its 8 vertices as dots
// of distinct colours. In its model frame the cube spans [-e/2, e/2]^3; `modelToWorld` places
// it. Edges are clipped at the near plane and, with view.distortion, bend through the lens (cut
// into <= 4 px pieces: projectSegmentThroughLens); drawn on top of the current viewport.
#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>

#include "render/PixelCanvas.hpp"
#include "render/SceneRenderer.hpp"

namespace reftrack::render {

struct WireframeCubeStyle {
  double edgeLength = 0.1;  // metres
  Eigen::Matrix4d modelToWorld = Eigen::Matrix4d::Identity();
  float lineWidthPx = 3.0f;
  cv::Scalar colourBgr{255, 128, 0};  // differs from every vertex colour
  bool vertexDots = true;
  float dotRadiusPx = 5.0f;
  void check() const;  // throws reftrack::Error naming the bad field
};

class WireframeCube {
 public:
  void draw(const PinholeView& view, const WireframeCubeStyle& style);

  // Vertex i of the cube in the world frame; bit 0/1/2 of i selects +x/+y/+z in the model frame.
  static std::array<Eigen::Vector3d, 8> worldVertices(const WireframeCubeStyle& style);
  // Red, green, blue, yellow, magenta, cyan, white, orange (BGR), for vertex 0..7.
  static const std::array<cv::Scalar, 8>& vertexColoursBgr();

 private:
  PixelCanvas canvas_;
};

}  // namespace reftrack::render
