#include "app/tracking/HomographyOverlay.hpp"

#include <glad/gl.h>

#include <cmath>
#include <limits>

#include "engine/homography/HomographyDlt.hpp"
#include "engine/homography/LensTransfer.hpp"

namespace reftrack::app {

namespace {

const cv::Scalar kOutlineColour(255, 200, 0);  // cyan-blue
const cv::Scalar kLabelColour(0, 255, 255);    // yellow
constexpr int kOutlineSamplesPerSide = 16;     // the outline bends under strong perspective

}  // namespace

HomographyOverlay::HomographyOverlay() = default;
HomographyOverlay::~HomographyOverlay() = default;

cv::Mat HomographyOverlay::composite(const cv::Mat& frame, const PinholeCamera& camera,
                                     const TrackingResult& result, const OverlaySettings& settings,
                                     const std::string& label, const std::optional<cv::Matx33d>& H,
                                     const AnnotationSet& labels, cv::Size referenceSize,
                                     bool referenceSharesCamera) {
  if (!target_ || target_->size() != frame.size())
    target_ = std::make_unique<render::RenderTarget>(frame.size());
  target_->bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  const render::Viewport viewport{0, 0, frame.cols, frame.rows};
  compositor_.draw(frame, camera, result, settings, viewport, label);
  if (H) {
    annotations_.clear();
    const float scale = std::max(1.0f, frame.rows / 240.0f);
    // The reference image's border, sampled along each side (a projective map keeps lines
    // straight, but points behind the camera must be dropped: the polyline breaks there).
    const cv::Size reference = referenceSize.area() > 0 ? referenceSize : frame.size();
    const double w = reference.width - 0.5, h = reference.height - 0.5;
    const cv::Point2d corners[4] = {{-0.5, -0.5}, {w, -0.5}, {w, h}, {-0.5, h}};
    // Through a lens H relates the undistorted images (HomographyFrameTracker): border and
    // labels are undistorted, mapped and distorted again (transferThroughLens), so the outline
    // bends as the lens bends the reference's border.
    const bool lens = camera.hasDistortion();
    const int samples = lens ? 4 * kOutlineSamplesPerSide : kOutlineSamplesPerSide;
    std::vector<cv::Point2d> border;
    for (int side = 0; side < 4; ++side)
      for (int i = 0; i < samples; ++i) {
        const double t = static_cast<double>(i) / samples;
        border.push_back(corners[side] * (1 - t) + corners[(side + 1) % 4] * t);
      }
    std::vector<cv::Point2d> mappedBorder;
    if (lens) {
      mappedBorder = transferThroughLens(*H, border, camera, referenceSharesCamera);
    } else {
      for (const cv::Point2d& p : border) {
        const double z = (*H)(2, 0) * p.x + (*H)(2, 1) * p.y + (*H)(2, 2);
        const double nan = std::numeric_limits<double>::quiet_NaN();
        mappedBorder.push_back(z > 0 ? transferPoint(*H, p) : cv::Point2d(nan, nan));
      }
    }
    std::vector<cv::Point2f> outline;
    bool closed = true;
    for (const cv::Point2d& q : mappedBorder)
      if (std::isfinite(q.x) && std::isfinite(q.y))
        outline.emplace_back(static_cast<float>(q.x), static_cast<float>(q.y));
      else
        closed = false;
    if (outline.size() >= 2) annotations_.addPolyline(outline, closed, scale, kOutlineColour);
    std::vector<cv::Point2d> positions;
    for (const Annotation& a : labels.labels()) positions.push_back(a.position);
    const std::vector<cv::Point2d> mapped =
        lens ? transferThroughLens(*H, positions, camera, referenceSharesCamera)
             : labels.mapped(*H);
    for (size_t i = 0; i < mapped.size(); ++i) {
      const cv::Point2d q = mapped[i];
      if (!std::isfinite(q.x) || !std::isfinite(q.y)) continue;
      const cv::Point2f at(static_cast<float>(q.x), static_cast<float>(q.y));
      annotations_.addDot(at, 3.0f * scale, kLabelColour);
      annotations_.addText(at + cv::Point2f(4.0f * scale, 4.0f * scale), labels.labels()[i].text,
                           kLabelColour, scale);
    }
    if (!annotations_.empty()) annotations_.draw(frame.size());
  }
  return target_->readColourBgr();
}

}  // namespace reftrack::app
