#pragma once
// OverlayCompositor: draws one composited frame — the video frame, then the virtual object (the
// wireframe cube or an OBJ model) for camera K and the tracked world->camera pose, then the 2-D
// debug layers (corners, matches, epipolar lines) and a status label — into the current render
// target (the debug layers and the label only when the settings turn them on: by default the
// picture is clean). Used by the viewer window, headless runs, `demo` and `track --record`. The
// overlay is projected through the camera's lens distortion (the cube's edges cut into short
// pieces), so it lands on the distorted video where the lens puts it
// (render::PinholeView::distortion). An uncertain pose (TrackingResult::uncertain: its predicted
// overlay error exceeds pose.max_predicted_error_px) is not drawn as if exact: the cube thin,
// grey and without its vertex dots, an OBJ model not at all, the label amber. Needs a current GL
// 3.3 context.
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "app/viewer/FrameTracker.hpp"
#include "app/viewer/OverlaySettings.hpp"
#include "engine/geometry/PinholeCamera.hpp"
#include "render/Annotations2D.hpp"
#include "render/ObjModel.hpp"
#include "render/RenderTarget.hpp"
#include "render/VideoBackground.hpp"
#include "render/Viewport.hpp"
#include "render/WireframeCube.hpp"

namespace reftrack::app {

class OverlayCompositor {
 public:
  OverlayCompositor();
  ~OverlayCompositor();
  OverlayCompositor(const OverlayCompositor&) = delete;
  OverlayCompositor& operator=(const OverlayCompositor&) = delete;

  // Draws into `viewport` of the framebuffer currently bound (the frame fills the viewport, so
  // give it the frame's aspect ratio: render::fitImage). `label` is shown top-left when
  // settings.showLabels. Throws reftrack::Error when the frame size differs from the camera's or
  // the model file cannot be loaded.
  void draw(const cv::Mat& frame, const PinholeCamera& camera, const TrackingResult& result,
            const OverlaySettings& settings, const render::Viewport& viewport,
            const std::string& label = "");

  // Composites off-screen at the frame's size and returns the BGR image (CV_8UC3).
  cv::Mat composite(const cv::Mat& frame, const PinholeCamera& camera, const TrackingResult& result,
                    const OverlaySettings& settings, const std::string& label = "");

 private:
  void drawObject(const render::PinholeView& view, const OverlaySettings& settings, bool uncertain);

  render::VideoBackground background_;
  render::WireframeCube cube_;
  render::Annotations2D annotations_;
  std::unique_ptr<render::ObjModel> model_;
  std::string modelPath_;
  std::unique_ptr<render::RenderTarget> target_;
};

}  // namespace reftrack::app
