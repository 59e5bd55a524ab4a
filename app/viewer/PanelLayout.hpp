#pragma once
// PanelLayout: where the ImGui panels and the video go on a canvas (window or headless
// framebuffer): Source, Tracking and Record panels in a left column, Overlay and Stats in a right
// column, the video letterboxed in between. With the Calibration panel, it takes the right column
// above Stats and Overlay moves to the left column, sharing Tracking's space. With the References
// panel (a multi-reference 6-DOF tracker), it sits in the right column just above Stats. Rectangles
// are in ImGui coordinates (origin top-left).
#include <opencv2/core.hpp>

#include "render/Viewport.hpp"

namespace reftrack::app {

struct PanelLayout {
  cv::Rect2f source, tracking, record, overlay, stats;
  cv::Rect2f calibration;  // empty without the Calibration panel
  cv::Rect2f references;   // empty without the References panel
  cv::Rect videoArea;      // top-left origin
};

// Throws reftrack::Error when the canvas is too small to hold both columns and some video.
PanelLayout panelLayout(cv::Size canvas, bool withCalibration = false, bool withReferences = false);

// The GL viewport (bottom-left origin) showing an image of `imageSize` letterboxed in `area` of
// a canvas of `canvas` pixels.
render::Viewport videoViewport(cv::Size imageSize, const cv::Rect& area, cv::Size canvas);

}  // namespace reftrack::app
