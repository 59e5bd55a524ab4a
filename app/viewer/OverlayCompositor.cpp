#include "app/viewer/OverlayCompositor.hpp"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {

const cv::Scalar kCornerColour(0, 220, 255);     // amber
const cv::Scalar kMatchColour(80, 255, 80);      // green
const cv::Scalar kEpipolarColour(255, 160, 60);  // light blue
const cv::Scalar kLabelColour(255, 255, 255);    // white
const cv::Scalar kLostLabelColour(80, 80, 255);  // red
// An uncertain pose (pose.max_predicted_error_px): the cube thin and grey, the label amber.
const cv::Scalar kUncertainCubeColour(150, 150, 150);
const cv::Scalar kUncertainLabelColour(0, 190, 255);

}  // namespace

OverlayCompositor::OverlayCompositor() = default;
OverlayCompositor::~OverlayCompositor() = default;

void OverlayCompositor::drawObject(const render::PinholeView& view, const OverlaySettings& settings,
                                   bool uncertain) {
  if (settings.modelPath.empty()) {
    render::WireframeCubeStyle style;
    style.edgeLength = settings.size;
    style.modelToWorld = settings.cubeModelToWorld();
    style.lineWidthPx = settings.lineWidthPx;
    style.vertexDots = settings.vertexDots;
    if (uncertain) {
      style.colourBgr = kUncertainCubeColour;
      style.lineWidthPx = std::max(1.0f, settings.lineWidthPx / 3);
      style.vertexDots = false;
    }
    cube_.draw(view, style);
    return;
  }
  if (uncertain) return;  // a shaded model cannot be dimmed: not drawn at all
  if (!model_ || modelPath_ != settings.modelPath) {
    model_.reset();
    model_ = std::make_unique<render::ObjModel>(settings.modelPath);
    modelPath_ = settings.modelPath;
  }
  render::ObjDrawOptions options;
  options.transform.scale = settings.size;
  // OBJ models are y-up; the object's up is its +z (out of the desk): rotate +90 deg about x,
  // then into the world by the object's orientation (the scene plane's, when placed on it).
  Eigen::Matrix3d yUpToZUp;
  yUpToZUp << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  options.transform.rotation = settings.orientation * yUpToZUp;
  options.transform.offset = settings.offset;
  glClear(GL_DEPTH_BUFFER_BIT);
  model_->draw(view, options);
}

void OverlayCompositor::draw(const cv::Mat& frame, const PinholeCamera& camera,
                             const TrackingResult& result, const OverlaySettings& settings,
                             const render::Viewport& viewport, const std::string& label) {
  settings.check();
  if (frame.empty()) throw Error("overlay: empty frame");
  if (frame.size() != camera.imageSize())
    throw Error("overlay: frame is " + std::to_string(frame.cols) + "x" +
                std::to_string(frame.rows) + " but the camera is calibrated for " +
                std::to_string(camera.imageSize().width) + "x" +
                std::to_string(camera.imageSize().height));
  render::applyViewport(viewport);
  background_.draw(frame);

  if (result.worldToCamera && result.worldToCamera->allFinite()) {
    render::PinholeView view;
    view.K = camera.K();
    view.imageSize = frame.size();
    view.worldToCamera = result.worldToCamera->matrix4();
    view.distortion = camera.distortion();  // the overlay bends as the lens bent the video
    drawObject(view, settings, result.uncertain);
  }

  annotations_.clear();
  const float scale = std::max(1.0f, frame.rows / 240.0f);
  if (settings.showEpipolarLines)
    for (const cv::Vec3d& l : result.debug.epipolarLines)
      annotations_.addInfiniteLine(l[0], l[1], l[2], frame.size(), scale, kEpipolarColour);
  if (settings.showMatches)
    for (const auto& [from, to] : result.debug.matches)
      annotations_.addSegment(from, to, scale, kMatchColour);
  if (settings.showCorners)
    for (const cv::Point2f& c : result.debug.corners)
      annotations_.addDot(c, 1.5f * scale, kCornerColour);
  if (settings.showLabels && !label.empty())
    annotations_.addText({4.0f * scale, 4.0f * scale}, label,
                         result.uncertain          ? kUncertainLabelColour
                         : result.status == "lost" ? kLostLabelColour
                                                   : kLabelColour,
                         scale);
  if (!annotations_.empty()) annotations_.draw(frame.size());
}

cv::Mat OverlayCompositor::composite(const cv::Mat& frame, const PinholeCamera& camera,
                                     const TrackingResult& result, const OverlaySettings& settings,
                                     const std::string& label) {
  if (frame.empty()) throw Error("overlay: empty frame");
  if (!target_ || target_->size() != frame.size())
    target_ = std::make_unique<render::RenderTarget>(frame.size());
  target_->bind();
  glClearColor(0, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  draw(frame, camera, result, settings, {0, 0, frame.cols, frame.rows}, label);
  return target_->readColourBgr();
}

}  // namespace reftrack::app
