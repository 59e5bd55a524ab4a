#pragma once
// OverlayPanel: the virtual object (wireframe cube or OBJ model), its placement (on the tracked
// scene's plane, or at an offset in the world frame; editing the offset places it by hand) and
// size (from the scene, or typed), line width, and the debug layers (one "Debug overlay" switch
// for corners, matches and labels, each also on its own; epipolar lines).
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "app/viewer/OverlaySettings.hpp"

namespace reftrack::app {

// The panel's own editing state: the object choice and the model path being typed (applied to
// the settings on Enter), and the tracked scene's placement (set by the viewer loop).
struct OverlayPanelEdit {
  bool useModel = false;
  std::string modelPath;
  std::string message;                  // e.g. why a model could not be loaded
  std::optional<ScenePlacement> scene;  // nullopt: no map (the offset and size are used)
};

void drawOverlayPanel(OverlaySettings& settings, OverlayPanelEdit& edit,
                      const cv::Rect2f& placement);

}  // namespace reftrack::app
