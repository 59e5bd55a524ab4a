#pragma once
// OverlayPanel: the virtual object (wireframe cube or OBJ model), its size and offset in the
// world frame, line width, and which debug layers are drawn (corners, matches, epipolar lines,
// labels).
#include <opencv2/core.hpp>
#include <string>

#include "app/viewer/OverlaySettings.hpp"

namespace reftrack::app {

// The panel's own editing state: the object choice and the model path being typed (applied to
// the settings on Enter).
struct OverlayPanelEdit {
  bool useModel = false;
  std::string modelPath;
  std::string message;  // e.g. why a model could not be loaded
};

void drawOverlayPanel(OverlaySettings& settings, OverlayPanelEdit& edit,
                      const cv::Rect2f& placement);

}  // namespace reftrack::app
