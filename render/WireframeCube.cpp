// Wireframe cube: CPU-projected edges expanded to pixel-space quads, vertex dots on top.
#include "render/WireframeCube.hpp"

#include <cmath>
#include <vector>

#include "engine/core/Error.hpp"
#include "render/CameraProjection.hpp"
#include "render/PointMarkers.hpp"

namespace reftrack::render {

void WireframeCubeStyle::check() const {
  if (!std::isfinite(edgeLength) || !(edgeLength > 0))
    throw Error("wireframe cube: edgeLength must be positive");
  if (!modelToWorld.allFinite()) throw Error("wireframe cube: modelToWorld has a non-finite entry");
  if (!std::isfinite(lineWidthPx) || !(lineWidthPx > 0))
    throw Error("wireframe cube: lineWidthPx must be positive");
  if (vertexDots && (!std::isfinite(dotRadiusPx) || !(dotRadiusPx > 0)))
    throw Error("wireframe cube: dotRadiusPx must be positive");
}

std::array<Eigen::Vector3d, 8> WireframeCube::worldVertices(const WireframeCubeStyle& style) {
  std::array<Eigen::Vector3d, 8> vertices;
  const double h = style.edgeLength / 2;
  for (int i = 0; i < 8; ++i) {
    const Eigen::Vector4d model((i & 1) ? h : -h, (i & 2) ? h : -h, (i & 4) ? h : -h, 1.0);
    vertices[i] = (style.modelToWorld * model).head<3>();
  }
  return vertices;
}

const std::array<cv::Scalar, 8>& WireframeCube::vertexColoursBgr() {
  static const std::array<cv::Scalar, 8> colours = {
      cv::Scalar(0, 0, 255),     cv::Scalar(0, 255, 0),   cv::Scalar(255, 0, 0),
      cv::Scalar(0, 255, 255),   cv::Scalar(255, 0, 255), cv::Scalar(255, 255, 0),
      cv::Scalar(255, 255, 255), cv::Scalar(0, 128, 255)};
  return colours;
}

void WireframeCube::draw(const PinholeView& view, const WireframeCubeStyle& style) {
  style.check();
  const auto vertices = worldVertices(style);
  canvas_.clear();
  const Eigen::Vector4f edgeColour = rgbaFromBgr(style.colourBgr);
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4}) {
      if (i & bit) continue;  // each edge once, from the vertex with that bit clear
      const auto edge = projectSegmentToPixels(view.K, view.worldToCamera, vertices[i],
                                               vertices[i | bit], view.nearPlane);
      if (!edge || !edge->first.allFinite() || !edge->second.allFinite()) continue;
      canvas_.addThickLine(edge->first.cast<float>(), edge->second.cast<float>(), style.lineWidthPx,
                           edgeColour);
    }
  if (style.vertexDots) {
    const auto& colours = vertexColoursBgr();
    addPointMarkers(canvas_, view, {vertices.begin(), vertices.end()},
                    {colours.begin(), colours.end()}, style.dotRadiusPx);
  }
  canvas_.draw(view.imageSize);
}

}  // namespace reftrack::render
