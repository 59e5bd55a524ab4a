#pragma once
// PointMarkers: world points drawn as filled dots of given colours and pixel radius, centred
// exactly on K(RX+t) (through view.distortion when given) (points not beyond the near plane are
// skipped). Drawn on top of everything in the current viewport. Needs a current GL 3.3 context.
#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "render/PixelCanvas.hpp"
#include "render/SceneRenderer.hpp"

namespace reftrack::render {

// Appends the dots to `canvas` (colours: one per point, or one for all). Throws reftrack::Error
// on a colour count mismatch or a radius <= 0.
void addPointMarkers(PixelCanvas& canvas, const PinholeView& view,
                     const std::vector<Eigen::Vector3d>& worldPoints,
                     const std::vector<cv::Scalar>& coloursBgr, float radiusPx);

class PointMarkers {
 public:
  void draw(const PinholeView& view, const std::vector<Eigen::Vector3d>& worldPoints,
            const std::vector<cv::Scalar>& coloursBgr, float radiusPx);

 private:
  PixelCanvas canvas_;
};

}  // namespace reftrack::render
