// Point markers: CPU projection with K, discs in pixel space.
#include "render/PointMarkers.hpp"

#include <string>

#include "engine/core/Error.hpp"
#include "render/CameraProjection.hpp"

namespace reftrack::render {

void addPointMarkers(PixelCanvas& canvas, const PinholeView& view,
                     const std::vector<Eigen::Vector3d>& worldPoints,
                     const std::vector<cv::Scalar>& coloursBgr, float radiusPx) {
  if (coloursBgr.size() != 1 && coloursBgr.size() != worldPoints.size())
    throw Error("point markers: " + std::to_string(coloursBgr.size()) + " colours for " +
                std::to_string(worldPoints.size()) + " points (give one, or one per point)");
  if (!(radiusPx > 0)) throw Error("point markers: radius must be positive");
  for (size_t i = 0; i < worldPoints.size(); ++i) {
    const auto pixel =
        projectToPixel(view.K, view.distortion, view.worldToCamera, worldPoints[i], view.nearPlane);
    if (!pixel || !pixel->allFinite()) continue;
    canvas.addDisc(pixel->cast<float>(), radiusPx,
                   rgbaFromBgr(coloursBgr.size() == 1 ? coloursBgr[0] : coloursBgr[i]));
  }
}

void PointMarkers::draw(const PinholeView& view, const std::vector<Eigen::Vector3d>& worldPoints,
                        const std::vector<cv::Scalar>& coloursBgr, float radiusPx) {
  canvas_.clear();
  addPointMarkers(canvas_, view, worldPoints, coloursBgr, radiusPx);
  canvas_.draw(view.imageSize);
}

}  // namespace reftrack::render
