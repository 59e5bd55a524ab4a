#include "app/viewer/PanelLayout.hpp"

#include <algorithm>

#include "engine/core/Error.hpp"

namespace reftrack::app {

namespace {
constexpr float kColumnWidth = 330.0f;
constexpr float kSourceHeight = 170.0f;
constexpr float kRecordHeight = 120.0f;
constexpr float kOverlayHeight = 300.0f;
constexpr float kStatsHeightBesideCalibration = 200.0f;
constexpr float kReferencesHeight = 250.0f;
constexpr int kMinimumVideoWidth = 160;
constexpr int kMinimumHeight = kSourceHeight + kRecordHeight + 200;
}  // namespace

PanelLayout panelLayout(cv::Size canvas, bool withCalibration, bool withReferences) {
  if (canvas.width < 2 * kColumnWidth + kMinimumVideoWidth || canvas.height < kMinimumHeight)
    throw Error("viewer canvas " + std::to_string(canvas.width) + "x" +
                std::to_string(canvas.height) + " is too small for the panels (at least " +
                std::to_string(static_cast<int>(2 * kColumnWidth) + kMinimumVideoWidth) + "x" +
                std::to_string(kMinimumHeight) + ")");
  const float w = static_cast<float>(canvas.width), h = static_cast<float>(canvas.height);
  PanelLayout l;
  l.source = {0, 0, kColumnWidth, kSourceHeight};
  l.tracking = {0, kSourceHeight, kColumnWidth, h - kSourceHeight - kRecordHeight};
  l.record = {0, h - kRecordHeight, kColumnWidth, kRecordHeight};
  l.overlay = {w - kColumnWidth, 0, kColumnWidth, kOverlayHeight};
  l.stats = {w - kColumnWidth, kOverlayHeight, kColumnWidth, h - kOverlayHeight};
  if (withCalibration) {
    const float shared = 0.5f * (h - kSourceHeight - kRecordHeight);
    l.tracking.height = shared;
    l.overlay = {0, kSourceHeight + shared, kColumnWidth, shared};
    l.calibration = {w - kColumnWidth, 0, kColumnWidth, h - kStatsHeightBesideCalibration};
    l.stats = {w - kColumnWidth, h - kStatsHeightBesideCalibration, kColumnWidth,
               kStatsHeightBesideCalibration};
  }
  if (withReferences) {
    // Taken from the panel above Stats (Overlay, or Calibration beside it).
    cv::Rect2f& above = withCalibration ? l.calibration : l.overlay;
    const float height = std::min(kReferencesHeight, 0.5f * above.height + 0.5f * l.stats.height);
    if (withCalibration) {
      above.height -= height;
    } else {
      l.stats.y += height;
      l.stats.height -= height;
    }
    l.references = {w - kColumnWidth, l.stats.y - height, kColumnWidth, height};
    if (withCalibration) l.references.y = above.y + above.height;
  }
  const int column = static_cast<int>(kColumnWidth);
  l.videoArea = {column, 0, canvas.width - 2 * column, canvas.height};
  return l;
}

render::Viewport videoViewport(cv::Size imageSize, const cv::Rect& area, cv::Size canvas) {
  render::Viewport v = render::fitImage(imageSize, area.size());
  v.x += area.x;
  v.y += canvas.height - (area.y + area.height);  // GL rows count from the bottom
  return v;
}

}  // namespace reftrack::app
